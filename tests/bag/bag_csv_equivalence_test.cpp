// A simulated car log written as a ROS 1 bag by ROS's own rosbag (tests/bag/write_log_as_bag.py)
// imports through examples/bag-joint-states/topics.yaml into the same log, and calibrates to the
// same circumferences, as the CSV log; a simulated robot's wheels written as twist odometry
// calibrate to the robot's truth. Labelled slow (drives and several calibrations).

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../support/run_cli.hpp"
#include "odocal/io/log_reader.hpp"
#include "scratch_dir.hpp"

namespace odocal::testing {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = ODOCAL_SOURCE_DIR;

std::string line_starting(const std::string& text, const std::string& prefix) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
    if (line.starts_with(prefix)) return line;
  return "(no line " + prefix + ")";
}

// ROS's own rosbag writes the CSV log as a bag (tests/bag/write_log_as_bag.py); `options` go to
// the script (e.g. --twist).
void write_log_as_bag(const fs::path& csv_log, const fs::path& bag,
                      const std::string& options = "") {
  const std::string command = "/usr/bin/python3 " +
                              (kSource / "tests/bag/write_log_as_bag.py").string() + " " +
                              csv_log.string() + " " + bag.string() + " " + options;
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
}

// One lap of the simulator's circuit car as a CSV log (wheels in rad, GNSS in lat/lon) and as a
// bag of it.
void simulate_car_bag(const fs::path& csv_log, const fs::path& bag,
                      const std::string& bag_options = "") {
  ASSERT_EQ(
      run_cli("simulate --laps 1 --wheel-output rad --gnss-output latlon --out " + csv_log.string())
          .status,
      0);
  ASSERT_NO_FATAL_FAILURE(write_log_as_bag(csv_log, bag, bag_options));
}

double parameter(const nlohmann::json& result, const std::string& name, const char* key) {
  for (const auto& p : result.at("parameters"))
    if (p.at("name") == name) return p.at(key).get<double>();
  return NAN;
}

TEST(BagImport, SimulatedLogAsBagGivesTheSameLogAndCalibration) {
  ScratchDir dir("sim");
  const fs::path csv_log = dir.path() / "csv-log";
  const fs::path bag = dir.path() / "drive.bag";
  const fs::path bag_log = dir.path() / "bag-log";
  ASSERT_NO_FATAL_FAILURE(simulate_car_bag(csv_log, bag));
  const CliRun import = run_cli("import bag " + bag.string() + " --map " +
                                (kSource / "examples/bag-joint-states/topics.yaml").string() +
                                " --out " + bag_log.string());
  ASSERT_EQ(import.status, 0) << import.err;

  const Log from_csv = read_log(csv_log);
  const Log from_bag = read_log(bag_log);
  ASSERT_EQ(from_bag.wheels.size(), from_csv.wheels.size());
  for (std::size_t k = 0; k < from_csv.wheels.size(); k += 97) {
    EXPECT_NEAR(from_bag.wheels.t_s[k], from_csv.wheels.t_s[k], 1e-6);
    EXPECT_NEAR(from_bag.wheels.rev_rl[k], from_csv.wheels.rev_rl[k], 1e-9);
  }
  ASSERT_EQ(from_bag.gnss.size(), from_csv.gnss.size());
  EXPECT_NEAR(from_bag.gnss.x_m[500], from_csv.gnss.x_m[500], 1e-3);
  EXPECT_NEAR(from_bag.gnss.sigma_m[500], from_csv.gnss.sigma_m[500], 1e-3);
  ASSERT_TRUE(from_bag.heading && from_bag.imu);
  EXPECT_NEAR(from_bag.heading->heading_rad[800], from_csv.heading->heading_rad[800], 1e-6);
  EXPECT_NEAR(from_bag.imu->wz_radps[800], from_csv.imu->wz_radps[800], 1e-6);

  for (const char* method : {"iterative", "batch"}) {
    const CliRun a = run_cli("calibrate " + csv_log.string() + " --method " + method);
    const CliRun b = run_cli("calibrate " + bag_log.string() + " --method " + method);
    EXPECT_EQ(a.status, b.status) << method;
    EXPECT_EQ(line_starting(a.out, "c_RL"), line_starting(b.out, "c_RL")) << method;
    EXPECT_EQ(line_starting(a.out, "c_RR"), line_starting(b.out, "c_RR")) << method;
  }
}

// A car's bag that places its sensors by tf (/tf_static, as its URDF publishes them): the IMU
// mounted on its side in imu_link under an intermediate chassis frame, the antenna in gps. The
// map names the frames instead of stating the mounting and the places, and the import turns the
// IMU's readings and its orientation's heading into the vehicle's frame as the CSV log has them,
// and writes the places into vehicle.yaml. A place stated twice, a frame tf lacks and a frame it
// does not connect to the base are errors naming the map's key.
TEST(BagImport, TfStaticPlacesAndMountsTheSensors) {
  ScratchDir dir("tf");
  const fs::path csv_log = dir.path() / "csv-log";
  const fs::path bag = dir.path() / "drive.bag";
  const fs::path bag_log = dir.path() / "bag-log";
  ASSERT_NO_FATAL_FAILURE(simulate_car_bag(csv_log, bag, "--tf --antenna 1.5,-0.4"));
  // The shipped map, then copies of it with one thing wrong.
  const fs::path shipped = kSource / "examples/bag-joint-states/topics-tf.yaml";
  const auto import_with = [&](const fs::path& map) {
    fs::remove_all(bag_log);
    return run_cli("import bag " + bag.string() + " --map " + map.string() + " --out " +
                   bag_log.string());
  };
  const CliRun import = import_with(shipped);
  ASSERT_EQ(import.status, 0) << import.err;

  const Log from_csv = read_log(csv_log);
  const Log from_bag = read_log(bag_log);
  ASSERT_TRUE(from_bag.vehicle.imu_position_m && from_bag.vehicle.gnss_position_m);
  EXPECT_NEAR(from_bag.vehicle.imu_position_m->x(), from_csv.vehicle.imu_position_m->x(), 1e-9);
  EXPECT_NEAR(from_bag.vehicle.imu_position_m->y(), 0.0, 1e-9);
  EXPECT_NEAR(from_bag.vehicle.gnss_position_m->x(), 1.5, 1e-9);
  EXPECT_NEAR(from_bag.vehicle.gnss_position_m->y(), -0.4, 1e-9);
  ASSERT_TRUE(from_bag.imu && from_bag.heading);
  ASSERT_EQ(from_bag.imu->size(), from_csv.imu->size());
  for (std::size_t k = 0; k < from_csv.imu->size(); k += 89) {
    EXPECT_NEAR(from_bag.imu->ax_mps2[k], from_csv.imu->ax_mps2[k], 1e-5) << k;
    EXPECT_NEAR(from_bag.imu->ay_mps2[k], from_csv.imu->ay_mps2[k], 1e-5) << k;
    EXPECT_NEAR(from_bag.imu->wz_radps[k], from_csv.imu->wz_radps[k], 1e-6) << k;
    EXPECT_NEAR(from_bag.heading->heading_rad[k], from_csv.heading->heading_rad[k], 1e-6) << k;
  }

  const std::string text = read_text_file(shipped.string());
  const auto expect_error = [&](const std::string& from, const std::string& to,
                                const std::string& key, const std::string& says) {
    std::string edited = text;
    edited.replace(edited.find(from), from.size(), to);
    std::ofstream(dir.path() / "topics.yaml") << edited;
    const CliRun run = import_with(dir.path() / "topics.yaml");
    EXPECT_EQ(run.status, 2) << to;
    EXPECT_NE(run.err.find(key), std::string::npos) << run.err;
    EXPECT_NE(run.err.find(says), std::string::npos) << run.err;
  };
  expect_error("gnss: gps", "gnss: antenna", "frames.gnss",
               "tf has no frame 'antenna' (it has 'base_link', 'chassis', 'gps', 'imu_link')");
  expect_error("base: base_link ", "base: odom ", "frames.imu",
               "tf does not connect frame 'imu_link' to 'odom'");
  expect_error("topic: /tf_static", "topic: /tf", "frames", "topic /tf is not in the bag");
  expect_error("wheelbase_m: 2.7", "wheelbase_m: 2.7\n  imu_y_m: 0.1", "frames.imu",
               "state it in one place");
}

// The tyres' force from the car's bus on a topic of its own (std_msgs/Float64, stamped with the
// bag's record time) becomes wheels.csv's drive_force_n, on the wheels' times, as the CSV log has
// it; a map naming a topic the bag lacks says so.
TEST(BagImport, ADriveForceTopicBecomesTheWheelsDriveForceColumn) {
  ScratchDir dir("force");
  const fs::path scenario = dir.path() / "urban-force.yaml";
  const fs::path csv_log = dir.path() / "csv-log";
  const fs::path bag = dir.path() / "drive.bag";
  const fs::path bag_log = dir.path() / "bag-log";
  std::ofstream(scenario) << read_text_file((kSource / "config/scenarios/urban.yaml").string())
                          << "sensors:\n  wheels:\n    drive_force_sigma_n: 100\n";
  ASSERT_EQ(run_cli("simulate --scenario " + scenario.string() +
                    " --laps 1 --wheel-output rad --gnss-output latlon --out " + csv_log.string())
                .status,
            0);
  ASSERT_NO_FATAL_FAILURE(write_log_as_bag(csv_log, bag));
  std::string map = read_text_file((kSource / "examples/bag-joint-states/topics.yaml").string());
  const std::string rr = "    rr: {joint: rear_right_wheel, unit: rad}\n";
  ASSERT_NE(map.find(rr), std::string::npos);
  map.replace(map.find(rr), rr.size(),
              rr + "    drive_force: {topic: /drive_force, field: data, unit: kN, scale: 0.001, "
                   "time: record}\n");
  std::ofstream(dir.path() / "topics.yaml") << map;
  const CliRun import =
      run_cli("import bag " + bag.string() + " --map " + (dir.path() / "topics.yaml").string() +
              " --out " + bag_log.string());
  ASSERT_EQ(import.status, 0) << import.err;
  const Log from_csv = read_log(csv_log), from_bag = read_log(bag_log);
  ASSERT_EQ(from_bag.wheels.size(), from_csv.wheels.size());
  ASSERT_EQ(from_bag.wheels.drive_force_n.size(), from_bag.wheels.size());
  for (std::size_t k = 0; k < from_csv.wheels.size(); k += 97)
    EXPECT_NEAR(from_bag.wheels.drive_force_n[k], from_csv.wheels.drive_force_n[k], 1e-3) << k;

  map.replace(map.find("/drive_force"), 12, "/vehicle/force");
  std::ofstream(dir.path() / "topics.yaml") << map;
  const CliRun missing =
      run_cli("import bag " + bag.string() + " --map " + (dir.path() / "topics.yaml").string() +
              " --out " + (dir.path() / "missing").string());
  EXPECT_EQ(missing.status, 2);
  EXPECT_NE(
      missing.err.find("'streams.wheels.drive_force': topic /vehicle/force is not in the bag"),
      std::string::npos)
      << missing.err;
}

// Twist odometry: the simulated skid-steer robot's wheels published as a drive controller's
// nav_msgs/Odometry twist (speed and yaw rate), imported through a twist map and calibrated with
// the robot configuration, finds the same effective track and odometry scales as its encoder log,
// and the truth, within 3 sigma.
TEST(BagImport, TwistOdometryOfASimulatedRobotCalibratesToItsTruth) {
  ScratchDir dir("twist");
  const fs::path csv_log = dir.path() / "csv-log";
  const fs::path bag = dir.path() / "robot.bag";
  const fs::path bag_log = dir.path() / "bag-log";
  ASSERT_EQ(run_cli("simulate --scenario robot --out " + csv_log.string()).status, 0);
  ASSERT_NO_FATAL_FAILURE(write_log_as_bag(csv_log, bag, "--twist"));
  const fs::path map = dir.path() / "topics.yaml";
  std::ofstream(map) << "vehicle: {track_width_m: 0.555, circumference_rl_m: 1.03735389422, "
                        "circumference_rr_m: 1.03735389422}\n"
                        "streams:\n"
                        "  wheels: {topic: /odom}\n"
                        "  gnss: {topic: /fix}\n"
                        "  imu: {topic: /imu/data}\n";
  ASSERT_EQ(run_cli("import bag " + bag.string() + " --map " + map.string() + " --out " +
                    bag_log.string())
                .status,
            0);
  const std::string config = (kSource / "examples/robot/calibrate.yaml").string();
  nlohmann::json results[2];
  for (int i = 0; i < 2; ++i) {
    const fs::path json = dir.path() / ("result" + std::to_string(i) + ".json");
    const CliRun run = run_cli("calibrate " + (i == 0 ? csv_log : bag_log).string() + " --config " +
                               config + " --json " + json.string());
    ASSERT_EQ(run.status, 0) << run.out << run.err;
    results[i] = nlohmann::json::parse(read_text_file(json.string()));
  }
  const double true_speed = (2 * 0.1651 - 0.0015 - 0.0005) / (2 * 0.1651);
  const double true_yaw = true_speed * 0.555 / 0.72;
  for (const nlohmann::json& result : results) {
    const double track = parameter(result, "track_width_m", "value");
    const double sigma_track = parameter(result, "track_width_m", "sigma");
    EXPECT_NEAR(track, 0.72, 3 * sigma_track);
    const auto& scales = result.at("odometry_scales");
    EXPECT_NEAR(scales.at("speed_scale").get<double>(), true_speed,
                3 * scales.at("sigma_speed_scale").get<double>());
    EXPECT_NEAR(scales.at("yaw_rate_scale").get<double>(), true_yaw,
                3 * scales.at("sigma_yaw_rate_scale").get<double>());
  }
  // The twist and the encoders tell the same story.
  EXPECT_NEAR(parameter(results[1], "track_width_m", "value"),
              parameter(results[0], "track_width_m", "value"),
              parameter(results[0], "track_width_m", "sigma"));
}

}  // namespace
}  // namespace odocal::testing
