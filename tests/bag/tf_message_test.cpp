// tf's static transforms as a ROS 2 bag stores them: tf2_msgs/msg/TFMessage in CDR, decoded with
// odocal's own definitions (a rosbag2 SQLite3 bag carries none) through the paths the importer's
// frames pass asks for. The ROS 1 path is checked end to end by BagImport.TfStaticPlacesAndMounts
// TheSensors (ROS's own rosbag writes it).

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "odocal/bag/message_decoder.hpp"

namespace odocal {
namespace {

// Little-endian CDR after the 4-byte encapsulation header: each primitive aligned to its size,
// counted from the header's end.
class CdrWriter {
 public:
  CdrWriter() : bytes_{0, 1, 0, 0} {}
  template <typename T>
  void put(T value) {
    while ((bytes_.size() - 4) % sizeof(T) != 0) bytes_.push_back(0);
    const auto* raw = reinterpret_cast<const std::uint8_t*>(&value);
    bytes_.insert(bytes_.end(), raw, raw + sizeof(T));
  }
  void put_string(const std::string& text) {
    put(static_cast<std::uint32_t>(text.size() + 1));
    bytes_.insert(bytes_.end(), text.begin(), text.end());
    bytes_.push_back(0);
  }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

void put_transform(CdrWriter& cdr, const std::string& parent, const std::string& child,
                   const double (&translation)[3], const double (&rotation)[4]) {
  cdr.put<std::int32_t>(1700000000);  // header.stamp
  cdr.put<std::uint32_t>(5);
  cdr.put_string(parent);
  cdr.put_string(child);
  for (double v : translation) cdr.put(v);
  for (double v : rotation) cdr.put(v);
}

TEST(TfMessage, DecodesFromCdrWithOdocalsOwnDefinitions) {
  CdrWriter cdr;
  cdr.put<std::uint32_t>(2);  // transforms
  put_transform(cdr, "base_link", "imu_link", {1.45, 0.0, 0.3}, {0.5, -0.5, -0.5, 0.5});
  put_transform(cdr, "base_link", "gps", {1.5, -0.4, 1.4}, {0.0, 0.0, 0.0, 1.0});
  const std::vector<std::string> paths = {
      "transforms.header.frame_id",         "transforms.child_frame_id",
      "transforms.transform.translation.x", "transforms.transform.translation.y",
      "transforms.transform.rotation.x",    "transforms.transform.rotation.w"};
  const bag::MessageDecoder decoder("tf2_msgs/msg/TFMessage", "", "", bag::MessageEncoding::kCdr,
                                    paths, "/tf_static");
  bag::DecodedFields out;
  decoder.decode(cdr.bytes(), out);
  ASSERT_EQ(out.strings[0], (std::vector<std::string>{"base_link", "base_link"}));
  ASSERT_EQ(out.strings[1], (std::vector<std::string>{"imu_link", "gps"}));
  EXPECT_EQ(out.numbers[2], (std::vector<double>{1.45, 1.5}));
  EXPECT_EQ(out.numbers[3], (std::vector<double>{0.0, -0.4}));
  EXPECT_EQ(out.numbers[4], (std::vector<double>{0.5, 0.0}));
  EXPECT_EQ(out.numbers[5], (std::vector<double>{0.5, 1.0}));

  // Cut inside the second transform: an error, not a short read.
  std::vector<std::uint8_t> cut = cdr.bytes();
  cut.resize(cut.size() - 20);
  EXPECT_THROW(decoder.decode(cut, out), bag::DecodeError);
}

}  // namespace
}  // namespace odocal
