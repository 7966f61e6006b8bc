// The container readers against bags written by ROS's own tools: rosbag2's MCAP and SQLite3
// fixtures with the values rosbag2's tests check, the real Husky ROS 1 bag (bz2), and ROS 1 bags
// written by Debian's python3-rosbag (stored, bz2, lz4). Shared fixtures are skipped when absent.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include "bag_test_support.hpp"
#include "mcap_builder.hpp"
#include "odocal/bag/bag_listing.hpp"
#include "odocal/error.hpp"

namespace odocal::testing {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

#define SKIP_WITHOUT(path) \
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << (path)

class Rosbag2Fixtures : public ::testing::TestWithParam<std::string> {};

// rosbag2's play end-to-end test: /test_topic BasicTypes x3 with int32_value 123, /array_topic
// Arrays x4 with bool_values {true, false, true} and the three "Complex Hello" strings.
TEST_P(Rosbag2Fixtures, CdrTestDecodesAsRosbag2sTestsExpect) {
  const auto bag = kSharedBags / GetParam() / "cdr_test";
  SKIP_WITHOUT(bag);
  const StoringVisitor all = read_all(bag);
  ASSERT_EQ(all.topics.size(), 2u);
  EXPECT_EQ(all.count("/test_topic"), 3u);
  EXPECT_EQ(all.count("/array_topic"), 4u);
  for (const auto& basic : all.decode("/test_topic", {"int32_value", "float64_value"})) {
    EXPECT_THAT(basic.numbers[0], ElementsAre(123.0));
  }
  // The whole Arrays message, nested BasicTypes/Constants/Defaults arrays included, decodes up
  // to its last field (CDR alignment after arrays: the message's own regression field).
  const auto arrays = all.decode(
      "/array_topic",
      {"bool_values", "string_values", "basic_types_values.int32_value", "alignment_check"});
  ASSERT_EQ(arrays.size(), 4u);
  for (const auto& message : arrays) {
    EXPECT_THAT(message.numbers[0], ElementsAre(1.0, 0.0, 1.0));
    EXPECT_THAT(message.strings[1],
                ElementsAre("Complex Hello1", "Complex Hello2", "Complex Hello3"));
    EXPECT_EQ(message.numbers[2].size(), 3u);
    EXPECT_EQ(message.numbers[3].size(), 1u);
  }
  // Record times are rosbag2's: the first at 1586406456763032325 ns.
  EXPECT_EQ(all.messages.front().time_ns, 1586406456763032325);
}

// The talker bags: "Hello, world! N" on /topic; the SQLite3 copy carries a broken definition
// ("String data"), so odocal's own std_msgs/String is used.
TEST_P(Rosbag2Fixtures, TalkerStringsDecode) {
  const auto bag = kSharedBags / GetParam() / "talker";
  SKIP_WITHOUT(bag);
  const StoringVisitor all = read_all(bag);
  const auto strings = all.decode("/topic", {"data"});
  ASSERT_EQ(strings.size(), 10u);
  for (std::size_t n = 0; n < strings.size(); ++n)
    EXPECT_THAT(strings[n].strings[0], ElementsAre("Hello, world! " + std::to_string(n)));
  EXPECT_EQ(all.count("/rosout"), 10u);
  EXPECT_EQ(all.count("/parameter_events"), 0u);
}

INSTANTIATE_TEST_SUITE_P(Storage, Rosbag2Fixtures, ::testing::Values("mcap", "sqlite3"));

TEST(Rosbag2Mcap, RosoutLogMessagesDecodeFromTheirSchema) {
  const auto bag = kSharedBags / "mcap/talker";
  SKIP_WITHOUT(bag);
  const auto logs = read_all(bag).decode("/rosout", {"stamp", "name", "msg", "line"});
  ASSERT_EQ(logs.size(), 10u);
  EXPECT_THAT(logs[3].strings[1], ElementsAre("minimal_publisher"));
  EXPECT_THAT(logs[3].strings[2], ElementsAre("Publishing: 'Hello, world! 3'"));
  EXPECT_NEAR(logs[3].numbers[0][0], 1585866236.6, 0.1);
}

// A bag split by size into five files, described by metadata.yaml: counts per topic as there.
TEST(Rosbag2Mcap, SplitBagReadsEveryFile) {
  const auto bag = kSharedBags / "mcap/wbag";
  SKIP_WITHOUT(bag);
  const bag::BagListing listing = bag::list_bag(bag);
  EXPECT_EQ(listing.files.files.size(), 5u);
  EXPECT_EQ(listing.message_count, 6074u);
  std::map<std::string, std::size_t> counts;
  for (const auto& topic : listing.topics) counts[topic.topic.name] = topic.count;
  EXPECT_EQ(counts, (std::map<std::string, std::size_t>{{"AAA", 804},
                                                        {"BBB", 742},
                                                        {"CCC", 742},
                                                        {"DDD", 753},
                                                        {"EEE", 804},
                                                        {"FFF", 772},
                                                        {"GGG", 731},
                                                        {"HHH", 726}}));
  // Every message of every file decodes as std_msgs/String.
  const StoringVisitor all = read_all(bag);
  EXPECT_EQ(all.decode("AAA", {"data"}).size(), 804u);
}

// The real Husky bag (bz2 chunks): counts, frames and the values its README states.
TEST(HuskyBag, ReadsAsItsReadmeDescribes) {
  SKIP_WITHOUT(kHuskyBag);
  const StoringVisitor all = read_all(kHuskyBag);
  EXPECT_EQ(all.count("/imu/data"), 11865u);
  EXPECT_EQ(all.count("/husky_velocity_controller/odom"), 3952u);
  EXPECT_EQ(all.count("/fix"), 989u);
  const auto imu = all.decode("/imu/data", {"header.frame_id", "linear_acceleration.y"});
  EXPECT_THAT(imu.front().strings[0], ElementsAre("imu_link"));
  double mean_ay = 0.0;
  for (const auto& m : imu) mean_ay += m.numbers[1][0] / static_cast<double>(imu.size());
  EXPECT_NEAR(mean_ay, 9.79, 0.02);  // the IMU's +y points up
  const auto odom = all.decode("/husky_velocity_controller/odom",
                               {"child_frame_id", "twist.twist.linear.y", "header.stamp"});
  EXPECT_THAT(odom.front().strings[0], ElementsAre("base_link"));
  for (const auto& m : odom) EXPECT_EQ(m.numbers[1][0], 0.0);
  EXPECT_NEAR(odom.front().numbers[2][0], 1432235498.0, 1.0);
  const auto fix =
      all.decode("/fix", {"latitude", "longitude", "status.status", "position_covariance_type"});
  EXPECT_NEAR(fix.front().numbers[0][0], 42.3758, 1e-3);
  EXPECT_NEAR(fix.front().numbers[1][0], -71.1474, 1e-3);
  EXPECT_EQ(fix.front().numbers[2][0], 1.0);
  EXPECT_EQ(fix.front().numbers[3][0], 1.0);
}

class WrittenRos1Bags : public ::testing::TestWithParam<std::string> {};

// Bags written by rosbag itself, in each chunk compression: every value as written.
TEST_P(WrittenRos1Bags, ValuesAsWritten) {
  const auto path = kWrittenBags / ("written_" + GetParam() + ".bag");
  ASSERT_TRUE(std::filesystem::exists(path)) << path;
  const StoringVisitor all = read_all(path);
  const auto imu = all.decode("/imu/data", {"header.stamp", "angular_velocity.z",
                                            "linear_acceleration.x", "header.frame_id"});
  ASSERT_EQ(imu.size(), 50u);
  for (std::size_t k = 0; k < imu.size(); ++k) {
    EXPECT_NEAR(imu[k].numbers[0][0], 1000.0 + 0.1 * static_cast<double>(k), 1e-9);
    EXPECT_DOUBLE_EQ(imu[k].numbers[1][0], 0.01 * static_cast<double>(k));
    EXPECT_DOUBLE_EQ(imu[k].numbers[2][0], static_cast<double>(k));
    EXPECT_THAT(imu[k].strings[3], ElementsAre("imu_link"));
  }
  const auto joints = all.decode("/joint_states", {"name", "position"});
  EXPECT_THAT(joints[7].strings[0], ElementsAre("rear_left_wheel", "rear_right_wheel"));
  EXPECT_THAT(joints[7].numbers[1], ElementsAre(0.1 * 7, 0.2 * 7));
  const auto fix = all.decode("/fix", {"latitude", "position_covariance"});
  ASSERT_EQ(fix.size(), 10u);
  EXPECT_DOUBLE_EQ(fix[3].numbers[0][0], 48.0 + 1e-5 * 15);
  EXPECT_THAT(fix[3].numbers[1], ElementsAre(0.25, 0, 0, 0, 0.25, 0, 0, 0, 1.0));
  const auto odom = all.decode("/odom", {"twist.twist.linear.x", "twist.twist.angular.z"});
  EXPECT_THAT(odom[9].numbers[0], ElementsAre(1.5));
  EXPECT_THAT(odom[9].numbers[1], ElementsAre(-0.25));
}

INSTANTIATE_TEST_SUITE_P(Compression, WrittenRos1Bags, ::testing::Values("none", "bz2", "lz4"));

// The cdr_test messages repackaged by the MCAP builder: outside chunks, in lz4 and zstd chunks,
// without summary; each layout decodes to the same values.
class McapLayouts : public ::testing::TestWithParam<std::string> {};

TEST_P(McapLayouts, SameMessagesInEveryLayout) {
  const auto source = kSharedBags / "mcap/cdr_test";
  SKIP_WITHOUT(source);
  const StoringVisitor original = read_all(source);
  McapBuilder builder;
  const std::string layout = GetParam();
  if (layout != "unchunked") builder.begin_chunk();
  for (std::size_t t = 0; t < original.topics.size(); ++t) {
    const auto id = static_cast<std::uint16_t>(t + 1);
    builder.schema(id, original.topics[t].type, original.topics[t].definition_format,
                   original.topics[t].definition);
    builder.channel(id, id, original.topics[t].name, "cdr");
  }
  for (const StoredMessage& m : original.messages)
    builder.message(static_cast<std::uint16_t>(m.topic + 1), static_cast<std::uint64_t>(m.time_ns),
                    m.data);
  if (layout != "unchunked") builder.end_chunk(layout == "stored" ? "" : layout);
  const std::vector<std::uint8_t> bytes = builder.finish();
  StoringVisitor copy;
  bag::read_mcap(bytes, "built.mcap", copy);
  ASSERT_EQ(copy.messages.size(), original.messages.size());
  for (std::size_t k = 0; k < copy.messages.size(); ++k) {
    EXPECT_EQ(copy.messages[k].data, original.messages[k].data);
    EXPECT_EQ(copy.messages[k].time_ns, original.messages[k].time_ns);
  }
  EXPECT_THAT(copy.decode("/test_topic", {"int32_value"})[2].numbers[0], ElementsAre(123.0));
}

INSTANTIATE_TEST_SUITE_P(Layout, McapLayouts,
                         ::testing::Values("unchunked", "stored", "lz4", "zstd"));

}  // namespace
}  // namespace odocal::testing
