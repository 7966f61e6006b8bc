#include "odocal/bag/bag_listing.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace odocal::bag {
namespace {

class ListingVisitor : public BagVisitor {
 public:
  explicit ListingVisitor(BagListing& listing) : listing_(listing) {}

  void topic(std::size_t index, const BagTopic& topic) override {
    listing_.topics.resize(std::max(listing_.topics.size(), index + 1));
    times_.resize(listing_.topics.size());
    listing_.topics[index].topic = topic;
  }

  void message(const BagMessage& message) override {
    times_[message.topic].push_back(message.record_time_ns);
    ++listing_.message_count;
    listing_.message_bytes += message.data.size();
  }

  void finish() {
    for (std::size_t t = 0; t < listing_.topics.size(); ++t) {
      std::vector<std::int64_t>& times = times_[t];
      TopicListing& topic = listing_.topics[t];
      topic.count = times.size();
      if (times.empty()) continue;
      std::sort(times.begin(), times.end());
      topic.first_ns = times.front();
      topic.last_ns = times.back();
      if (times.size() < 2) continue;
      std::vector<std::int64_t> steps(times.size() - 1);
      for (std::size_t k = 1; k < times.size(); ++k) steps[k - 1] = times[k] - times[k - 1];
      const auto middle = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
      std::nth_element(steps.begin(), middle, steps.end());
      if (*middle > 0) topic.median_rate_hz = 1e9 / static_cast<double>(*middle);
    }
  }

 private:
  BagListing& listing_;
  std::vector<std::vector<std::int64_t>> times_;
};

}  // namespace

BagListing list_bag(const std::filesystem::path& path) {
  BagListing listing;
  listing.files = locate_bag(path);
  ListingVisitor visitor(listing);
  read_bag(path, visitor);
  visitor.finish();
  return listing;
}

std::string format_bag_listing(const BagListing& listing) {
  std::string out =
      fmt::format("{}, {} file(s), {} messages, {:.1f} MB of message data\n",
                  bag_format_name(listing.files.format), listing.files.files.size(),
                  listing.message_count, static_cast<double>(listing.message_bytes) / 1e6);
  std::size_t topic_width = 5;
  std::size_t type_width = 4;
  for (const TopicListing& t : listing.topics) {
    topic_width = std::max(topic_width, t.topic.name.size());
    type_width = std::max(type_width, t.topic.type.size());
  }
  out += fmt::format("{:<{}}  {:<{}}  {:<8} {:>8} {:>9} {:>10} {:>20}\n", "topic", topic_width,
                     "type", type_width, "encoding", "count", "rate Hz", "span s", "first (s)");
  for (const TopicListing& t : listing.topics) {
    out += fmt::format("{:<{}}  {:<{}}  {:<8} {:>8} {:>9.2f} {:>10.3f} {:>20.3f}\n", t.topic.name,
                       topic_width, t.topic.type, type_width, t.topic.encoding, t.count,
                       t.median_rate_hz, static_cast<double>(t.last_ns - t.first_ns) * 1e-9,
                       static_cast<double>(t.first_ns) * 1e-9);
  }
  return out;
}

}  // namespace odocal::bag
