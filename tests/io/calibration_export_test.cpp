// Exported calibrations: the ROS 2 multipliers in closed form, vehicle.yaml read back, and the
// result JSON's errors naming the field.

#include "odocal/io/calibration_export.hpp"

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
