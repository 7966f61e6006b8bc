// Broken bags: each is an InputError naming the file and where (byte offset or record), never a
// crash or a silent partial read. Built from the generated ROS 1 bags and MCAP builder files.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "bag_test_support.hpp"
#include "mcap_builder.hpp"
#include "odocal/error.hpp"

namespace odocal::testing {
namespace {

using ::testing::HasSubstr;

std::string ros1_error(const std::vector<std::uint8_t>& bytes) {
  StoringVisitor visitor;
  try {
    bag::read_ros1_bag(bytes, "broken.bag", visitor);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string mcap_error(const std::vector<std::uint8_t>& bytes) {
  StoringVisitor visitor;
  try {
    bag::read_mcap(bytes, "broken.mcap", visitor);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::size_t find_text(const std::vector<std::uint8_t>& bytes, std::string_view text,
                      std::size_t from = 0) {
  const auto it = std::search(bytes.begin() + static_cast<std::ptrdiff_t>(from), bytes.end(),
                              text.begin(), text.end());
  return static_cast<std::size_t>(it - bytes.begin());
}

TEST(Ros1BagErrors, WrongMagicAndOtherVersions) {
  std::vector<std::uint8_t> bytes = file_bytes(kWrittenBags / "written_bz2.bag");
  bytes[1] = 'X';
  EXPECT_THAT(ros1_error(bytes), HasSubstr("broken.bag: byte 0: not a ROS 1 bag"));
  bytes[1] = 'R';
  bytes[10] = '1';  // "#ROSBAG V1.2"
  EXPECT_THAT(ros1_error(bytes), HasSubstr("format other than 2.0"));
}

TEST(Ros1BagErrors, EveryTruncationIsAnError) {
  const std::vector<std::uint8_t> whole = file_bytes(kWrittenBags / "written_bz2.bag");
  // Cut the file at many points: inside the header, a chunk, the index.
  for (std::size_t cut = 5; cut < whole.size(); cut += whole.size() / 37 + 1) {
    const std::vector<std::uint8_t> part(whole.begin(), whole.begin() + static_cast<long>(cut));
    const std::string error = ros1_error(part);
    EXPECT_THAT(error, HasSubstr("broken.bag: ")) << "cut at " << cut;
    EXPECT_THAT(error, HasSubstr("byte ")) << "cut at " << cut;
  }
}

TEST(Ros1BagErrors, CorruptChunkAndUnknownCompression) {
  std::vector<std::uint8_t> bytes = file_bytes(kWrittenBags / "written_bz2.bag");
  const std::size_t bz2 = find_text(bytes, "compression=bz2");
  ASSERT_LT(bz2, bytes.size());
  std::vector<std::uint8_t> unknown = bytes;
  unknown[bz2 + 12] = 'x';
  unknown[bz2 + 13] = 'z';
  EXPECT_THAT(ros1_error(unknown), HasSubstr("unknown chunk compression 'xz2'"));
  // Damage the first chunk's compressed data (after "BZh" at its start).
  const std::size_t data = find_text(bytes, "BZh", bz2);
  ASSERT_LT(data + 200, bytes.size());
  for (std::size_t i = data + 40; i < data + 60; ++i) bytes[i] ^= 0x5a;
  EXPECT_THAT(ros1_error(bytes), HasSubstr("bz2 chunk"));
}

TEST(Ros1BagErrors, ChunkSizeFieldThatLies) {
  std::vector<std::uint8_t> bytes = file_bytes(kWrittenBags / "written_lz4.bag");
  const std::size_t size = find_text(bytes, "size=");
  ASSERT_LT(size, bytes.size());
  bytes[size + 5] ^= 0x01;  // the uncompressed size is off by one
  EXPECT_THAT(ros1_error(bytes), HasSubstr("lz4 chunk"));
}

std::vector<std::uint8_t> small_mcap(std::string_view compression) {
  McapBuilder builder;
  builder.begin_chunk();
  builder.schema(1, "std_msgs/msg/String", "ros2msg", "string data");
  builder.channel(1, 1, "/topic", "cdr");
  const std::vector<std::uint8_t> hello = {0, 1, 0, 0, 6, 0, 0, 0, 'h', 'e', 'l', 'l', 'o', 0};
  for (int k = 0; k < 20; ++k) builder.message(1, 1000 + static_cast<std::uint64_t>(k), hello);
  builder.end_chunk(compression);
  return builder.finish();
}

TEST(McapErrors, WrongMagicTruncationAndMissingFooter) {
  std::vector<std::uint8_t> bytes = small_mcap("zstd");
  EXPECT_EQ(mcap_error(bytes), "no error");
  std::vector<std::uint8_t> bad_magic = bytes;
  bad_magic[1] = 'X';
  EXPECT_THAT(mcap_error(bad_magic), HasSubstr("broken.mcap: byte 0: not an MCAP file"));
  for (std::size_t cut = 8; cut + 8 < bytes.size(); cut += 7) {
    const std::vector<std::uint8_t> part(bytes.begin(), bytes.begin() + static_cast<long>(cut));
    EXPECT_THAT(mcap_error(part), HasSubstr("broken.mcap: ")) << "cut at " << cut;
  }
}

TEST(McapErrors, CrcMismatchAndUnknownCompression) {
  std::vector<std::uint8_t> stored = small_mcap("");
  const std::size_t hello = find_text(stored, "hello");
  ASSERT_LT(hello, stored.size());
  stored[hello] = 'j';
  EXPECT_THAT(mcap_error(stored), HasSubstr("chunk CRC mismatch"));

  std::vector<std::uint8_t> unknown = small_mcap("zstd");
  const std::size_t name = find_text(unknown, "zstd");
  unknown[name + 1] = 'x';
  EXPECT_THAT(mcap_error(unknown), HasSubstr("unknown chunk compression 'zxtd'"));
}

TEST(McapErrors, MessageBeforeItsChannel) {
  McapBuilder builder;
  const std::vector<std::uint8_t> data = {0, 1, 0, 0};
  builder.message(7, 1, data);
  EXPECT_THAT(mcap_error(builder.finish()), HasSubstr("channel 7 before its channel record"));
}

TEST(Sqlite3Errors, NotABagDatabase) {
  StoringVisitor visitor;
  const std::string garbage = "SQLite format 3 then nothing useful at all";
  const std::vector<std::uint8_t> bytes(garbage.begin(), garbage.end());
  EXPECT_THROW(bag::read_sqlite3_bag(bytes, "broken.db3", visitor), InputError);
}

TEST(BagFiles, MissingFileDirectoryWithoutBagsAndUnknownFile) {
  StoringVisitor visitor;
  EXPECT_THROW(bag::read_bag("/nonexistent/x.bag", visitor), InputError);
  const auto dir = std::filesystem::temp_directory_path() / "odocal_empty_bag_dir";
  std::filesystem::create_directories(dir);
  try {
    bag::read_bag(dir, visitor);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("no metadata.yaml"));
  }
  { std::ofstream(dir / "notes.bag") << "hello"; }
  EXPECT_THROW(bag::read_bag(dir, visitor), InputError);
  std::filesystem::remove_all(dir);
}

TEST(MessageDecoderErrors, TruncatedCountsAndUnknownFields) {
  const bag::MessageDecoder decoder("sensor_msgs/msg/JointState", "", "",
                                    bag::MessageEncoding::kCdr, {"name", "position"}, "/joints");
  bag::DecodedFields out;
  // Header (stamp, empty frame id), then a name array claiming 4e9 strings.
  std::vector<std::uint8_t> data = {0, 1, 0, 0, 1, 0, 0, 0, 0,    0,    0,    0,
                                    1, 0, 0, 0, 0, 0, 0, 0, 0xff, 0xff, 0xff, 0xf0};
  EXPECT_THROW(decoder.decode(data, out), bag::DecodeError);
  data.resize(10);
  EXPECT_THROW(decoder.decode(data, out), bag::DecodeError);
  const std::vector<std::uint8_t> xcdr2 = {0, 7, 0, 0, 0, 0, 0, 0};
  try {
    decoder.decode(xcdr2, out);
    ADD_FAILURE() << "no error";
  } catch (const bag::DecodeError& e) {
    EXPECT_THAT(e.what(), HasSubstr("encapsulation"));
  }
  try {
    bag::MessageDecoder("sensor_msgs/msg/Imu", "", "", bag::MessageEncoding::kCdr,
                        {"angular_velocity.w"}, "/imu");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("geometry_msgs/Vector3 has no field 'w' (it has x, y, z)"));
  }
  EXPECT_THROW(bag::MessageDecoder("sensor_msgs/msg/Imu", "", "", bag::MessageEncoding::kCdr,
                                   {"angular_velocity"}, "/imu"),
               InputError);
  EXPECT_THROW(bag::MessageDecoder("my_msgs/msg/Unknown", "", "", bag::MessageEncoding::kCdr, {"x"},
                                   "/mine"),
               InputError);
}

TEST(MessageDefinitions, ConstantsDefaultsBoundsAndComments) {
  const std::string definition =
      "# a comment line\n"
      "int32 FIRST=1   # a constant is not serialised\n"
      "string NAME=with # inside\n"
      "uint8[<=3] bounded\n"
      "string<=8 short_text \"default\"\n"
      "float64 value 2.5 # default\n";
  const bag::MessageDecoder decoder("pkg/msg/Thing", definition, "ros2msg",
                                    bag::MessageEncoding::kCdr, {"bounded", "short_text", "value"},
                                    "/thing");
  // CDR: bounded count 2 + 2 bytes, pad to 4, string "ab" (3 with NUL), pad to 8, float64.
  const std::vector<std::uint8_t> data = {0, 1, 0,   0,   2, 0, 0, 0, 7, 9, 0, 0, 3,    0,
                                          0, 0, 'a', 'b', 0, 0, 0, 0, 0, 0, 0, 0, 0x10, 0x40};
  bag::DecodedFields out;
  decoder.decode(data, out);
  EXPECT_THAT(out.numbers[0], ::testing::ElementsAre(7.0, 9.0));
  EXPECT_THAT(out.strings[1], ::testing::ElementsAre("ab"));
  EXPECT_THAT(out.numbers[2], ::testing::ElementsAre(4.0));
}

}  // namespace
}  // namespace odocal::testing
