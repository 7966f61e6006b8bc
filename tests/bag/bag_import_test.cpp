// `odocal import bag`: the real Husky bag imports through examples/husky/topics.yaml with its IMU
// turned upright; map mistakes are one-line errors and write nothing.

#include "odocal/bag/bag_import.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "../support/run_cli.hpp"
#include "bag_test_support.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/io/log_reader.hpp"
#include "scratch_dir.hpp"

namespace odocal::testing {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

const fs::path kSource = ODOCAL_SOURCE_DIR;

// The Husky's IMU is mounted with its +y up (README): turned into the body frame, gravity
// leaves the horizontal accelerations and the gyro's yaw rate is the one the odometry reports,
// which a skid-steer under-reports by about 0.75 (README: odom_wz = 0.75 gyro_wy).
TEST(BagImport, HuskyImuTurnedUprightAgreesWithTheOdometry) {
  if (!fs::exists(kHuskyBag)) GTEST_SKIP() << "shared data absent: " << kHuskyBag;
  ScratchDir dir("husky");
  const fs::path out = dir.path() / "log";
  const ImportSummary summary =
      bag::import_bag(kSource / "examples/husky/topics.yaml", kHuskyBag, out);
  ASSERT_EQ(summary.streams.size(), 3u);
  EXPECT_EQ(summary.streams[0].rows, 3952u);
  EXPECT_EQ(summary.streams[1].rows, 989u);
  EXPECT_EQ(summary.streams[2].rows, 11865u);
  const Log log = read_log(out);
  ASSERT_TRUE(log.imu);
  double mean_ax = 0, mean_ay = 0;
  for (std::size_t k = 0; k < log.imu->size(); ++k) {
    mean_ax += log.imu->ax_mps2[k] / static_cast<double>(log.imu->size());
    mean_ay += log.imu->ay_mps2[k] / static_cast<double>(log.imu->size());
  }
  EXPECT_LT(std::hypot(mean_ax, mean_ay), 0.5);
  // Odometry yaw rate (wheel speed difference over the nominal track) against the gyro.
  double sxy = 0, sxx = 0;
  const double track = log.vehicle.track_width_m;
  const double c = log.vehicle.circumference_rl_m;
  for (std::size_t k = 1; k < log.wheels.size(); ++k) {
    const double dt = log.wheels.t_s[k] - log.wheels.t_s[k - 1];
    const double odom_wz = (log.wheels.rev_rr[k] - log.wheels.rev_rl[k]) * c / track / dt;
    const double t = 0.5 * (log.wheels.t_s[k] + log.wheels.t_s[k - 1]);
    const std::optional<double> gyro_wz = interpolate_linear(log.imu->t_s, log.imu->wz_radps, t);
    if (!gyro_wz) continue;
    sxy += odom_wz * *gyro_wz;
    sxx += *gyro_wz * *gyro_wz;
  }
  EXPECT_NEAR(sxy / sxx, 0.75, 0.05);
}

class MapMistakes : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kWrittenBags / "written_none.bag")) GTEST_SKIP() << "no written bags";
  }
  std::string import_error(const std::string& map) {
    const fs::path map_file = dir_.path() / "map.yaml";
    std::ofstream(map_file) << map;
    fs::remove_all(dir_.path() / "out");
    try {
      bag::import_bag(map_file, kWrittenBags / "written_none.bag", dir_.path() / "out");
    } catch (const InputError& e) {
      EXPECT_FALSE(fs::exists(dir_.path() / "out")) << "nothing is written on an error";
      return e.what();
    }
    return "no error";
  }
  static std::string map_with(const std::string& streams) {
    return "vehicle: {track_width_m: 1.6, circumference_rl_m: 1.96, circumference_rr_m: 1.96}\n"
           "streams:\n" +
           streams;
  }
  ScratchDir dir_{"mistakes"};
};

TEST_F(MapMistakes, EachIsOneLineNamingTheKey) {
  const std::string wheels =
      "  wheels: {topic: /joint_states, rl: {joint: rear_left_wheel, unit: rad}, "
      "rr: {joint: rear_right_wheel, unit: rad}}\n";
  EXPECT_EQ(import_error(map_with(wheels + "  gnss: {topic: /fix}\n")), "no error");
  EXPECT_THAT(import_error(map_with(wheels + "  gnss: {topic: /gps}\n")),
              HasSubstr("topic /gps is not in the bag (it has /imu/data, /joint_states, /fix, "
                        "/odom)"));
  EXPECT_THAT(import_error(map_with(wheels + "  gnss: {topic: /imu/data}\n")),
              HasSubstr("'streams.gnss': topic /imu/data is sensor_msgs/Imu; gnss reads "
                        "sensor_msgs/NavSatFix"));
  EXPECT_THAT(
      import_error(map_with("  wheels: {topic: /joint_states, rl: {joint: left, unit: rad}, "
                            "rr: {joint: right, unit: rad}}\n  gnss: {topic: /fix}\n")),
      HasSubstr("gives 0 usable message(s)"));
  EXPECT_THAT(import_error(map_with(wheels + "  gnss: {topic: /fix, colour: red}\n")),
              HasSubstr("colour"));
  EXPECT_THAT(import_error(map_with("  wheels: {topic: /joint_states, rl: {joint: rear_left_wheel, "
                                    "unit: m/s}, rr: {joint: rear_right_wheel, unit: rad}}\n"
                                    "  gnss: {topic: /fix}\n")),
              HasSubstr("'streams.wheels.rl.unit': expected one of"));
  // rosbag's Odometry carries a zero quaternion here: no usable orientation.
  EXPECT_THAT(import_error(map_with(wheels + "  gnss: {topic: /fix}\n  heading: {topic: /odom}\n")),
              HasSubstr("gives 0 usable message(s) for heading"));
}

TEST(BagImportCli, ListAndBadBagExitCodes) {
  if (!fs::exists(kWrittenBags / "written_bz2.bag")) GTEST_SKIP() << "no written bags";
  const CliRun list =
      run_cli("import bag " + (kWrittenBags / "written_bz2.bag").string() + " --list");
  EXPECT_EQ(list.status, 0);
  EXPECT_THAT(list.out, HasSubstr("/joint_states"));
  const CliRun missing = run_cli("import bag /nonexistent.bag --list");
  EXPECT_EQ(missing.status, 2);
  EXPECT_THAT(missing.err, HasSubstr("/nonexistent.bag"));
  const CliRun no_map = run_cli("import bag " + (kWrittenBags / "written_bz2.bag").string());
  EXPECT_EQ(no_map.status, 2);
  EXPECT_THAT(no_map.err, HasSubstr("--map"));
}

}  // namespace
}  // namespace odocal::testing
