#pragma once
// What a bag holds (`odocal import bag BAG --list`): per topic its type, serialisation, message
// count, rate and time span by record time.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "odocal/bag/bag_reader.hpp"

namespace odocal::bag {

struct TopicListing {
  BagTopic topic;
  std::size_t count{};
  std::int64_t first_ns{};
  std::int64_t last_ns{};
  double median_rate_hz{};  // from the median spacing of record times; 0 below two messages
};

struct BagListing {
  BagFileSet files;
  std::vector<TopicListing> topics;  // in order of first appearance
  std::size_t message_count{};
  std::uint64_t message_bytes{};  // serialised message data, uncompressed
};

BagListing list_bag(const std::filesystem::path& path);

// The listing as an aligned table, one topic per line.
std::string format_bag_listing(const BagListing& listing);

}  // namespace odocal::bag
