#pragma once
// Reading ROS bags without ROS (docs/importing.md, "ROS bags"): ROS 1 bags (format 2.0,
// uncompressed, bz2 and lz4 chunks), ROS 2 MCAP files (chunked or not, zstd or lz4, with or
// without a summary) and ROS 2 SQLite3 files (.db3), alone or as a rosbag2 directory whose
// metadata.yaml lists its split files.
//
// One pass over the messages in file order (chunk by chunk; not sorted by time): topics are
// announced as they are first met, each message refers to its topic by index. Bad input (wrong
// magic, truncated records, a bad CRC or length, an unknown compression) is an InputError that
// names the file and the byte offset or record.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace odocal::bag {

enum class BagFormat { kRos1, kMcap, kSqlite3 };
const char* bag_format_name(BagFormat format);

// A topic as the bag describes it. Topics of the same name in several files of a split bag are
// one topic.
struct BagTopic {
  std::string name;      // "/imu/data"
  std::string type;      // as written by the bag: "sensor_msgs/Imu" or "sensor_msgs/msg/Imu"
  std::string encoding;  // message serialisation: "ros1" or "cdr"
  // The message definition the bag carries ("" when none) and its format ("ros1msg",
  // "ros2msg"); the decoder falls back to odocal's own definitions of the types it imports.
  std::string definition;
  std::string definition_format;
};

struct BagMessage {
  std::size_t topic{};                 // index into the topics announced so far
  std::int64_t record_time_ns{};       // when the recorder received it (bag time), ns since epoch
  std::span<const std::uint8_t> data;  // the serialised message; valid during the callback
};

class BagVisitor {
 public:
  virtual ~BagVisitor() = default;
  // Called once per topic, before its first message; indices count 0, 1, 2, ...
  virtual void topic(std::size_t index, const BagTopic& topic) = 0;
  virtual void message(const BagMessage& message) = 0;
};

struct BagFileSet {
  BagFormat format{};
  std::vector<std::filesystem::path> files;  // in reading order
};

// Which format and files `path` holds: a .bag, .mcap or .db3 file (by its magic bytes), or a
// directory (rosbag2's metadata.yaml, else every bag file in it by name).
BagFileSet locate_bag(const std::filesystem::path& path);

// Reads every message of the bag at `path` (a file or directory) in one pass.
void read_bag(const std::filesystem::path& path, BagVisitor& visitor);

// The container readers on bytes in memory (the fuzz harnesses; `name` is for messages).
void read_ros1_bag(std::span<const std::uint8_t> bytes, const std::string& name,
                   BagVisitor& visitor);
void read_mcap(std::span<const std::uint8_t> bytes, const std::string& name, BagVisitor& visitor);
void read_sqlite3_bag(std::span<const std::uint8_t> bytes, const std::string& name,
                      BagVisitor& visitor);

}  // namespace odocal::bag
