// `odocal calibrate --method batch` with its exports, then `odocal validate` on a different drive
// of the same car: the calibration must cut the held-out drift.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "../support/run_cli.hpp"
#include "../support/temp_log_dir.hpp"

namespace odocal {
namespace {

using testing::read_text_file;
using testing::run_cli;

TEST(ValidateCli, CalibrationOnOneDriveCutsDriftOnAnother) {
  testing::TempLogDir dir;
  const std::string circuit = dir.file("circuit"), urban = dir.file("urban");
  ASSERT_EQ(
      run_cli("simulate --scenario circuit --ideal --laps 1 --wear-rl 1.5 --wear-rr 1 --out " +
              circuit)
          .status,
      0);
  ASSERT_EQ(
      run_cli("simulate --scenario urban --ideal --wear-rl 1.5 --wear-rr 1 --seed 2 --out " + urban)
          .status,
      0);
  const auto calibrate = run_cli("calibrate " + circuit + " --method batch --json " +
                                 dir.file("result.json") + " --vehicle-out " +
                                 dir.file("vehicle.yaml") + " --ros2-out " + dir.file("ros2.yaml"));
  ASSERT_EQ(calibrate.status, 0) << calibrate.err;
  EXPECT_NE(calibrate.out.find("observable   every requested parameter identified"),
            std::string::npos)
      << calibrate.out;
  const auto result = nlohmann::json::parse(read_text_file(dir.file("result.json")));
  EXPECT_EQ(result["method"], "batch");
  EXPECT_TRUE(result.contains("parameters"));
  EXPECT_NE(read_text_file(dir.file("ros2.yaml")).find("left_wheel_radius_multiplier"),
            std::string::npos);

  const auto validate = run_cli("validate " + urban + " --params " + dir.file("result.json") +
                                " --window 60 --json " + dir.file("validation.json"));
  ASSERT_EQ(validate.status, 0) << validate.err;
  const auto v = nlohmann::json::parse(read_text_file(dir.file("validation.json")));
  EXPECT_GT(v["nominal"]["windows"].get<int>(), 3);
  EXPECT_LT(v["calibrated"]["median_drift_percent"].get<double>(),
            0.5 * v["nominal"]["median_drift_percent"].get<double>());

  // --config gives the reference options: looser heading and IMU noise change the reference, a bad
  // key is exit 2 naming the file.
  dir.write("config.yaml", "reference: {heading_sigma_rad: 3, acc_sigma_mps2: 5}\n");
  const auto configured = run_cli("validate " + urban + " --params " + dir.file("result.json") +
                                  " --config " + dir.file("config.yaml"));
  ASSERT_EQ(configured.status, 0) << configured.err;
  EXPECT_NE(configured.out, validate.out);
  dir.write("typo.yaml", "reference: {gnss_sigma: 10}\n");
  const auto typo = run_cli("validate " + urban + " --params " + dir.file("result.json") +
                            " --config " + dir.file("typo.yaml"));
  EXPECT_EQ(typo.status, 2);
  EXPECT_NE(typo.err.find("typo.yaml:1: 'reference.gnss_sigma': unknown key"), std::string::npos)
      << typo.err;

  const auto bad = run_cli("validate " + urban + " --params " + dir.file("ros2.yaml"));
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("ros2.yaml"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace odocal
