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
  // On an ideal drive the calibrated odometry is all but exact: what is left is the reference's
  // error, which its own covariance must predict. 24 overlapping windows (4 disjoint ones are too
  // few for a median): 1.09 times the prediction on this seed, 0.85-2.1 on urban seeds 1-10.
  EXPECT_NE(validate.out.find("the reference's own uncertainty"), std::string::npos)
      << validate.out;
  ASSERT_EQ(run_cli("validate " + urban + " --params " + dir.file("result.json") +
                    " --step 10 --json " + dir.file("overlapping.json"))
                .status,
            0);
  const auto overlapping = nlohmann::json::parse(read_text_file(dir.file("overlapping.json")));
  const double predicted =
      overlapping["reference_uncertainty"]["median_drift_percent"].get<double>();
  const double measured = overlapping["calibrated"]["median_drift_percent"].get<double>();
  EXPECT_GT(measured, 0.7 * predicted);
  EXPECT_LT(measured, 1.6 * predicted);
  EXPECT_GT(overlapping["nominal"]["median_drift_percent"].get<double>(), 2.0 * predicted);
  EXPECT_GT(overlapping["windows"][0]["reference_rms_m"].get<double>(), 0.0);

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

TEST(ValidateCli, TyreModelTravelsFromCalibrateToVehicleYamlDeadreckonAndValidate) {
  // A realistic (slipping, load-sensitive) lap of a rear-driven car: the extended tyre model's
  // coefficients go into vehicle.yaml, deadreckon applies them, the ROS 2 file says it cannot.
  testing::TempLogDir dir;
  const std::string log = dir.file("circuit");
  ASSERT_EQ(run_cli("simulate --scenario circuit --laps 1 --out " + log).status, 0);
  dir.write("extended.yaml", "batch: {tyre_model: extended, max_sigma_circumference_m: 0.01}\n");
  const auto calibrate =
      run_cli("calibrate " + log + " --method batch --config " + dir.file("extended.yaml") +
              " --json " + dir.file("result.json") + " --vehicle-out " + dir.file("vehicle.yaml") +
              " --ros2-out " + dir.file("ros2.yaml"));
  ASSERT_EQ(calibrate.status, 0) << calibrate.out << calibrate.err;
  const std::string vehicle = read_text_file(dir.file("vehicle.yaml"));
  EXPECT_NE(vehicle.find("tyre_model:\n  k_speed_s2pm2: "), std::string::npos) << vehicle;
  EXPECT_NE(read_text_file(dir.file("ros2.yaml")).find("cannot be carried"), std::string::npos);

  dir.write("circuit/vehicle.yaml", vehicle);
  const auto with_model = run_cli("deadreckon " + log);
  ASSERT_EQ(with_model.status, 0) << with_model.err;
  EXPECT_NE(with_model.out.find("with vehicle.yaml's tyre_model"), std::string::npos);
  const auto plain = run_cli("deadreckon " + log + " --plain");
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_EQ(plain.out.find("tyre_model"), std::string::npos);
  EXPECT_NE(plain.out, with_model.out);

  const auto validate = run_cli("validate " + log + " --params " + dir.file("result.json"));
  ASSERT_EQ(validate.status, 0) << validate.err;
  EXPECT_NE(validate.out.find("tyre model   the result's"), std::string::npos) << validate.out;
}

}  // namespace
}  // namespace odocal
