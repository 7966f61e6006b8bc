// A simulated car log written as a ROS 1 bag by ROS's own rosbag (tests/bag/write_log_as_bag.py)
// imports through examples/bag-joint-states/topics.yaml into the same log, and calibrates to the
// same circumferences, as the CSV log. Labelled slow (a drive and four calibrations).

#include <gtest/gtest.h>

#include <cstdlib>
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

TEST(BagImport, SimulatedLogAsBagGivesTheSameLogAndCalibration) {
  ScratchDir dir("sim");
  const fs::path csv_log = dir.path() / "csv-log";
  const fs::path bag = dir.path() / "drive.bag";
  const fs::path bag_log = dir.path() / "bag-log";
  ASSERT_EQ(
      run_cli("simulate --laps 1 --wheel-output rad --gnss-output latlon --out " + csv_log.string())
          .status,
      0);
  ASSERT_EQ(
      std::system(("/usr/bin/python3 " + (kSource / "tests/bag/write_log_as_bag.py").string() +
                   " " + csv_log.string() + " " + bag.string())
                      .c_str()),
      0);
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

}  // namespace
}  // namespace odocal::testing
