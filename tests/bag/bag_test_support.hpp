#pragma once
// Helpers for the bag tests: a visitor that keeps every topic and message, decoding by topic,
// and where the shared fixtures and the generated ROS 1 bags live.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "odocal/bag/bag_reader.hpp"
#include "odocal/bag/message_decoder.hpp"

namespace odocal::testing {

inline const std::filesystem::path kSharedBags =
    std::filesystem::path(ODOCAL_SOURCE_DIR) / "../shared/data/bags/rosbag2";
inline const std::filesystem::path kHuskyBag =
    std::filesystem::path(ODOCAL_SOURCE_DIR) / "../shared/data/real/husky-rl-test1/test1.bag";
// Written by tests/bag/write_ros1_bags.py (a ctest fixture) with ROS's own rosbag.
inline const std::filesystem::path kWrittenBags = ODOCAL_WRITTEN_BAGS_DIR;

struct StoredMessage {
  std::size_t topic{};
  std::int64_t time_ns{};
  std::vector<std::uint8_t> data;
};

class StoringVisitor : public bag::BagVisitor {
 public:
  void topic(std::size_t index, const bag::BagTopic& topic) override {
    if (topics.size() <= index) topics.resize(index + 1);
    topics[index] = topic;
  }
  void message(const bag::BagMessage& message) override {
    messages.push_back(
        {message.topic, message.record_time_ns, {message.data.begin(), message.data.end()}});
  }

  std::size_t topic_index(const std::string& name) const {
    for (std::size_t t = 0; t < topics.size(); ++t)
      if (topics[t].name == name) return t;
    throw std::runtime_error("no topic " + name);
  }

  std::size_t count(const std::string& name) const {
    const std::size_t index = topic_index(name);
    std::size_t n = 0;
    for (const StoredMessage& m : messages) n += m.topic == index;
    return n;
  }

  // Decodes every message of `name` with the bag's own definition.
  std::vector<bag::DecodedFields> decode(const std::string& name,
                                         const std::vector<std::string>& paths) const {
    const bag::BagTopic& topic = topics[topic_index(name)];
    const bag::MessageDecoder decoder(topic.type, topic.definition, topic.definition_format,
                                      bag::message_encoding_from_name(topic.encoding, name), paths,
                                      name);
    std::vector<bag::DecodedFields> out;
    for (const StoredMessage& m : messages) {
      if (m.topic != topic_index(name)) continue;
      decoder.decode(m.data, out.emplace_back());
    }
    return out;
  }

  std::vector<bag::BagTopic> topics;
  std::vector<StoredMessage> messages;
};

inline StoringVisitor read_all(const std::filesystem::path& path) {
  StoringVisitor visitor;
  bag::read_bag(path, visitor);
  return visitor;
}

inline std::vector<std::uint8_t> file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace odocal::testing
