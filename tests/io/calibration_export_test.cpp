// Exported calibrations: the ROS 2 multipliers in closed form, vehicle.yaml read back, and the
// result JSON's errors naming the field.

#include "odocal/io/calibration_export.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "../support/run_cli.hpp"
#include "../support/temp_log_dir.hpp"
#include "odocal/error.hpp"
#include "odocal/io/vehicle_config_io.hpp"

namespace odocal {
namespace {

VehicleConfig nominal_vehicle() {
  VehicleConfig v;
  v.track_width_m = 1.6;
  v.circumference_rl_m = v.circumference_rr_m = 2.0 * std::numbers::pi * 0.3126;
  v.ticks_per_rev = 96;
  return v;
}

TEST(CalibrationExport, WritesRos2MultipliersOfTheNominalGeometry) {
  testing::TempLogDir dir;
  const VehicleConfig nominal = nominal_vehicle();
  const OdometryParams calibrated{nominal.circumference_rl_m * 0.995,
                                  nominal.circumference_rr_m * 0.997, 1.62};
  write_ros2_diff_drive_parameters(nominal, calibrated, dir.file("ros2.yaml"));
  const std::string text = testing::read_text_file(dir.file("ros2.yaml"));
  EXPECT_NE(text.find("diff_drive_controller:\n  ros__parameters:\n"), std::string::npos) << text;
  EXPECT_NE(text.find("wheel_radius: 0.312600\n"), std::string::npos) << text;
  EXPECT_NE(text.find("wheel_separation: 1.600000\n"), std::string::npos) << text;
  EXPECT_NE(text.find("left_wheel_radius_multiplier: 0.99500000\n"), std::string::npos) << text;
  EXPECT_NE(text.find("right_wheel_radius_multiplier: 0.99700000\n"), std::string::npos) << text;
  EXPECT_NE(text.find("wheel_separation_multiplier: 1.01250000\n"), std::string::npos) << text;
}

TEST(CalibrationExport, UpdatedVehicleYamlKeepsEveryOtherKey) {
  testing::TempLogDir dir;
  const OdometryParams calibrated{1.9546, 1.9578, 1.61};
  write_calibrated_vehicle(nominal_vehicle(), calibrated, dir.file("vehicle-new.yaml"));
  const VehicleConfig back = read_vehicle_config(dir.file("vehicle-new.yaml"));
  EXPECT_NEAR(back.circumference_rl_m, 1.9546, 1e-9);
  EXPECT_NEAR(back.circumference_rr_m, 1.9578, 1e-9);
  EXPECT_NEAR(back.track_width_m, 1.61, 1e-9);
  ASSERT_TRUE(back.ticks_per_rev.has_value());
  EXPECT_EQ(*back.ticks_per_rev, 96);
}

TEST(CalibrationExport, TyreModelGoesToVehicleYamlAndIsSaidMissingInRos2) {
  testing::TempLogDir dir;
  const VehicleConfig nominal = nominal_vehicle();
  const OdometryParams calibrated{1.9546, 1.9578, 1.6};
  const TyreModel tyre{-3e-6, 5e-5, 0.0114, 0.0067, -0.04, 8e-4, 6e-4};
  write_calibrated_vehicle(nominal, calibrated, dir.file("vehicle-new.yaml"), tyre);
  const VehicleConfig back = read_vehicle_config(dir.file("vehicle-new.yaml"));
  ASSERT_TRUE(back.tyre_model.has_value());
  EXPECT_EQ(back.tyre_model->coefficients(), tyre.coefficients());
  // A plain calibration drops an earlier model: its circumferences mean something else.
  write_calibrated_vehicle(back, calibrated, dir.file("vehicle-plain.yaml"));
  EXPECT_FALSE(read_vehicle_config(dir.file("vehicle-plain.yaml")).tyre_model.has_value());
  write_ros2_diff_drive_parameters(nominal, calibrated, dir.file("ros2.yaml"), tyre);
  const std::string text = testing::read_text_file(dir.file("ros2.yaml"));
  EXPECT_NE(text.find("cannot be carried by diff_drive_controller"), std::string::npos) << text;
  write_ros2_diff_drive_parameters(nominal, calibrated, dir.file("ros2-plain.yaml"));
  EXPECT_EQ(testing::read_text_file(dir.file("ros2-plain.yaml")).find("cannot be carried"),
            std::string::npos);
}

TEST(CalibrationExport, Ros2GetsTheCircumferencesRollingAtTheReferenceSpeed) {
  // Constant radii stand for the tyre model in gentle driving: the circumferences rolling at
  // the calibration's reference speed, not the extrapolation to rest.
  testing::TempLogDir dir;
  const VehicleConfig nominal = nominal_vehicle();
  const OdometryParams calibrated{1.9546, 1.9578, 1.6};
  TyreModel tyre;
  tyre.k_drive_slip = 0.05;
  ReferenceCircumference rolling;
  rolling.speed_mps = 5.0;
  rolling.circumference_rl_m = 0.99 * nominal.circumference_rl_m;
  rolling.circumference_rr_m = 0.98 * nominal.circumference_rr_m;
  write_ros2_diff_drive_parameters(nominal, calibrated, dir.file("ros2.yaml"), tyre, rolling);
  const std::string text = testing::read_text_file(dir.file("ros2.yaml"));
  EXPECT_NE(text.find("left_wheel_radius_multiplier: 0.99000000\n"), std::string::npos) << text;
  EXPECT_NE(text.find("right_wheel_radius_multiplier: 0.98000000\n"), std::string::npos) << text;
  EXPECT_NE(text.find("rolling straight at a steady\n# 5 m/s"), std::string::npos) << text;
  // Without a tyre model the circumferences are constant: any rolling figure is not used.
  write_ros2_diff_drive_parameters(nominal, calibrated, dir.file("ros2-plain.yaml"), {}, rolling);
  EXPECT_NE(testing::read_text_file(dir.file("ros2-plain.yaml"))
                .find(fmt::format("left_wheel_radius_multiplier: {:.8f}\n",
                                  calibrated.circumference_rl_m / nominal.circumference_rl_m)),
            std::string::npos);
}

TEST(CalibrationExport, ResultJsonTyreModelIsItsEstimatedCoefficients) {
  testing::TempLogDir dir;
  std::ofstream(dir.file("result.json")) << R"({"parameters": [
      {"name": "tyre_drive_s2pm", "value": 0.011, "estimated": true},
      {"name": "tyre_turn_s2prad2", "value": -0.04, "estimated": true},
      {"name": "tyre_brake_lateral_s4pm2", "value": 6e-4, "estimated": true},
      {"name": "tyre_speed_s2pm2", "value": 5.0, "estimated": false}]})";
  const TyreModel model = read_calibrated_tyre_model(dir.file("result.json"));
  EXPECT_EQ(model.k_drive_s2pm, 0.011);
  EXPECT_EQ(model.k_turn_s2prad2, -0.04);
  EXPECT_EQ(model.k_brake_lateral_s4pm2, 6e-4);
  EXPECT_EQ(model.k_speed_s2pm2, 0.0);  // not estimated: held at zero
  std::ofstream(dir.file("absurd.json"))
      << R"({"parameters": [{"name": "tyre_brake_s2pm", "value": 7, "estimated": true}]})";
  try {
    read_calibrated_tyre_model(dir.file("absurd.json"));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().field, "parameters.tyre_brake_s2pm");
  }
}

TEST(CalibrationExport, ResultJsonErrorsNameTheField) {
  testing::TempLogDir dir;
  std::ofstream(dir.file("result.json"))
      << R"({"circumference_rl_m": 1.95, "circumference_rr_m": -1, "track_width_m": 1.6})";
  try {
    read_calibrated_parameters(dir.file("result.json"));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().field, "circumference_rr_m");
  }
  std::ofstream(dir.file("broken.json")) << "{";
  EXPECT_THROW(read_calibrated_parameters(dir.file("broken.json")), InputError);
  EXPECT_THROW(read_calibrated_parameters(dir.file("missing.json")), InputError);
}

}  // namespace
}  // namespace odocal
