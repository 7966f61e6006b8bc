// A simulated skid-steer robot (the built-in `robot` scenario: effective track 1.3x the
// geometric one, worn wheels) calibrated with examples/robot/calibrate.yaml: the batch finds the
// effective track, the circumferences and the odometry scales within 3 sigma of the truth, and
// the ROS 2 export carries the track as diff_drive_controller's wheel_separation_multiplier.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../support/run_cli.hpp"

namespace odocal::testing {
namespace {

namespace fs = std::filesystem;

TEST(RobotCalibration, SkidSteerEffectiveTrackAndScalesWithinThreeSigma) {
  const fs::path dir = fs::temp_directory_path() / "odocal_robot_calibration";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string log = (dir / "log").string();
  ASSERT_EQ(run_cli("simulate --scenario robot --out " + log).status, 0);
  const std::string config = std::string(ODOCAL_SOURCE_DIR) + "/examples/robot/calibrate.yaml";
  const std::string json = (dir / "result.json").string();
  const std::string ros2 = (dir / "ros2.yaml").string();
  const CliRun run = run_cli("calibrate " + log + " --config " + config + " --json " + json +
                             " --ros2-out " + ros2);
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  const nlohmann::json result = nlohmann::json::parse(read_text_file(json));

  // Truth of the scenario (config/scenarios/robot.yaml): radius 0.1651 m less 1.5 / 0.5 mm of
  // wear, track 0.555 m geometric, 0.72 m effective.
  constexpr double kTwoPi = 6.283185307179586;
  const double c_rl = kTwoPi * (0.1651 - 0.0015), c_rr = kTwoPi * (0.1651 - 0.0005);
  const double c0 = kTwoPi * 0.1651;
  double track = 0, sigma_track = 0;
  for (const auto& p : result.at("parameters")) {
    if (p.at("name") == "track_width_m") {
      track = p.at("value").get<double>();
      sigma_track = p.at("sigma").get<double>();
    }
  }
  EXPECT_NEAR(track, 0.72, 3 * sigma_track);
  EXPECT_LT(sigma_track, 0.01);
  EXPECT_NEAR(result.at("circumference_rl_m").get<double>(), c_rl,
              3 * result.at("sigma_circumference_rl_m").get<double>());
  EXPECT_NEAR(result.at("circumference_rr_m").get<double>(), c_rr,
              3 * result.at("sigma_circumference_rr_m").get<double>());
  const auto& scales = result.at("odometry_scales");
  const double true_speed = (c_rl + c_rr) / (2 * c0);
  EXPECT_NEAR(scales.at("speed_scale").get<double>(), true_speed,
              3 * scales.at("sigma_speed_scale").get<double>());
  EXPECT_NEAR(scales.at("yaw_rate_scale").get<double>(), true_speed * 0.555 / 0.72,
              3 * scales.at("sigma_yaw_rate_scale").get<double>());

  const std::string exported = read_text_file(ros2);
  const auto at = exported.find("wheel_separation_multiplier: ");
  ASSERT_NE(at, std::string::npos) << exported;
  EXPECT_NEAR(std::stod(exported.substr(at + 29)), 0.72 / 0.555, 0.03);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace odocal::testing
