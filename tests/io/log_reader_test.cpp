// The log reader accepts the documented format and rejects each malformed case with one line
// naming file, line and column. Each case starts from a valid tiny log and breaks one thing.

#include "odocal/io/log_reader.hpp"

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

using testing::TempLogDir;

struct ExpectedError {
  std::string file;  // file name inside the log directory
  std::size_t line;  // 0: whole file
  std::string field;
  std::string says;  // a phrase the problem must contain
};

void expect_input_error(const TempLogDir& log, const ExpectedError& expected) {
  try {
    read_log(log.path());
    FAIL() << "expected an InputError about " << expected.file;
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().file, log.file(expected.file)) << e.what();
    EXPECT_EQ(e.location().line, expected.line) << e.what();
    EXPECT_EQ(e.location().field, expected.field) << e.what();
    EXPECT_NE(e.problem().find(expected.says), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << "one line: " << e.what();
  }
}

TEST(LogReader, ReadsTheBaselineLog) {
  const TempLogDir dir;
  const Log log = read_log(dir.path());
  EXPECT_DOUBLE_EQ(log.vehicle.track_width_m, 1.6);
  ASSERT_EQ(log.wheels.size(), 4u);
  EXPECT_DOUBLE_EQ(log.wheels.rev_rl[0], 0.0);
  EXPECT_DOUBLE_EQ(log.wheels.rev_rl[1], 0.5);
  EXPECT_DOUBLE_EQ(log.wheels.rev_rr[3], 0.5);
  EXPECT_TRUE(log.wheels.rev_fl.empty());
  EXPECT_EQ(log.gnss.size(), 4u);
  EXPECT_FALSE(log.imu || log.heading || log.truth);
}

TEST(LogReader, ReadsEveryOptionalStream) {
  const TempLogDir dir;
  dir.write("imu.csv", "t,ax,ay,wz\n0.5,0.1,-0.2,0.01\n1.5,0.0,0.0,0.0\n");
  dir.write("heading.csv", "t,heading\n0.0,7.0\n");
  dir.write("truth.csv", "t,x,y,heading\n0.0,0,0,0\n3.0,3,0,0\n");
  const Log log = read_log(dir.path());
  ASSERT_TRUE(log.imu && log.heading && log.truth);
  EXPECT_DOUBLE_EQ(log.imu->wz_radps[0], 0.01);
  EXPECT_NEAR(log.heading->heading_rad[0], 7.0 - 2 * std::numbers::pi, 1e-12);
  EXPECT_DOUBLE_EQ(log.truth->pose[1].x(), 3.0);
}

TEST(LogReader, ConvertsEveryWheelUnitToRevolutions) {
  const TempLogDir dir;
  // Same motion as the baseline: 0.5 rev/s on a 2 m wheel = 1 m/s = pi rad/s.
  dir.write("wheels.csv",
            "t,rl_rad,rr_rad,fl_radps,fr_radps\n0,0,0,3.141592653589793,3.141592653589793\n"
            "1,3.141592653589793,3.141592653589793,3.141592653589793,3.141592653589793\n");
  Log log = read_log(dir.path());
  EXPECT_NEAR(log.wheels.rev_rl[1], 0.5, 1e-12);
  EXPECT_NEAR(log.wheels.rev_fr[1], 0.5, 1e-12);
  dir.write("wheels.csv", "t,rl_mps,rr_mps\n0,1,1\n1,1,1\n2,3,1\n");
  log = read_log(dir.path());
  EXPECT_NEAR(log.wheels.rev_rl[1], 0.5, 1e-12);
  EXPECT_NEAR(log.wheels.rev_rl[2], 1.0, 1e-12);  // trapezoid: (1 + 3) / 2 m over 2 m
  EXPECT_NEAR(log.wheels.rev_rr[2], 0.5, 1e-12);
}

TEST(LogReader, SignedTicksMeanReversing) {
  const TempLogDir dir;
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks\n0,0,0\n1,-48,-24\n");
  const Log log = read_log(dir.path());
  EXPECT_DOUBLE_EQ(log.wheels.rev_rl[1], -0.5);
  EXPECT_DOUBLE_EQ(log.wheels.rev_rr[1], -0.25);
}

TEST(LogReader, UnwrapsCounterWrapAround) {
  const TempLogDir dir;
  dir.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\nticks_per_rev: 96\n"
            "counter_bits: 16\n");
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks\n0,65500,10\n1,12,58\n2,65530,10\n");
  const Log log = read_log(dir.path());
  EXPECT_DOUBLE_EQ(log.wheels.rev_rl[1], 48.0 / 96);   // 65500 -> 65536 + 12
  EXPECT_DOUBLE_EQ(log.wheels.rev_rl[2], -18.0 / 96);  // backwards across the wrap
  EXPECT_DOUBLE_EQ(log.wheels.rev_rr[1], 48.0 / 96);
}

TEST(LogReader, ConvertsLatLonToLocalEnuAroundTheFirstFix) {
  const TempLogDir dir;
  // 0.001 deg of latitude is about 110.6 m north; 0.001 deg of longitude at 49 deg is ~73.1 m.
  dir.write("gnss.csv", "t,lat,lon,sigma_m\n0,49.0,8.0,2.5\n1,49.001,8.0,2.5\n2,49.0,8.001,2.5\n");
  const Log log = read_log(dir.path());
  ASSERT_TRUE(log.gnss.origin.has_value());
  EXPECT_DOUBLE_EQ(log.gnss.origin->latitude_deg, 49.0);
  EXPECT_NEAR(log.gnss.x_m[0], 0.0, 1e-9);
  EXPECT_NEAR(log.gnss.y_m[1], 111.25, 0.1);
  EXPECT_NEAR(log.gnss.x_m[1], 0.0, 1e-3);
  EXPECT_NEAR(log.gnss.x_m[2], 73.1, 0.1);
  EXPECT_DOUBLE_EQ(log.gnss.sigma_m[2], 2.5);
}

// --- missing files and columns --------------------------------------------------------------

TEST(LogReaderRejects, MissingDirectory) {
  EXPECT_THROW(read_log("/nonexistent/odocal/log"), InputError);
}

TEST(LogReaderRejects, MissingVehicleYaml) {
  const TempLogDir dir;
  dir.remove("vehicle.yaml");
  expect_input_error(dir, {"vehicle.yaml", 0, "", "cannot open"});
}

TEST(LogReaderRejects, MissingWheelsCsv) {
  const TempLogDir dir;
  dir.remove("wheels.csv");
  expect_input_error(dir, {"wheels.csv", 0, "", "cannot open"});
}

TEST(LogReaderRejects, MissingGnssCsv) {
  const TempLogDir dir;
  dir.remove("gnss.csv");
  expect_input_error(dir, {"gnss.csv", 0, "", "cannot open"});
}

TEST(LogReaderRejects, MissingRearWheelColumn) {
  const TempLogDir dir;
  dir.write("wheels.csv", "t,rl_ticks\n0,0\n1,48\n");
  expect_input_error(dir, {"wheels.csv", 1, "rr_*", "rr_ticks, rr_rad"});
}

TEST(LogReaderRejects, MissingTimeColumn) {
  const TempLogDir dir;
  dir.write("gnss.csv", "x,y\n0,0\n");
  expect_input_error(dir, {"gnss.csv", 1, "t", "missing"});
}

TEST(LogReaderRejects, MissingRequiredVehicleKey) {
  const TempLogDir dir;
  dir.write("vehicle.yaml", "track_width_m: 1.6\ncircumference_rl_m: 2.0\n");
  expect_input_error(dir, {"vehicle.yaml", 0, "circumference_rr_m", "missing"});
}

TEST(LogReaderRejects, TicksWithoutTicksPerRev) {
  const TempLogDir dir;
  dir.write("vehicle.yaml", "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\n");
  expect_input_error(dir, {"vehicle.yaml", 0, "ticks_per_rev", "rl_ticks"});
}

TEST(LogReaderRejects, UnknownColumn) {
  const TempLogDir dir;
  dir.write("gnss.csv", "t,x,y,sigma\n0,0,0,1\n");
  expect_input_error(dir, {"gnss.csv", 1, "sigma", "unknown column"});
}

TEST(LogReaderRejects, WheelGivenTwice) {
  const TempLogDir dir;
  dir.write("wheels.csv", "t,rl_ticks,rl_rad,rr_ticks\n0,0,0,0\n1,1,1,1\n");
  expect_input_error(dir, {"wheels.csv", 1, "rl_rad", "given twice"});
}

TEST(LogReaderRejects, BothMetricAndGeodeticGnss) {
  const TempLogDir dir;
  dir.write("gnss.csv", "t,x,y,lat,lon\n0,0,0,49,8\n");
  expect_input_error(dir, {"gnss.csv", 1, "", "not both"});
}

// --- malformed values ---------------------------------------------------------------------

TEST(LogReaderRejects, UnparsableNumber) {
  const TempLogDir dir;
  dir.write("gnss.csv", "t,x,y\n0,0,0\n1,1.0.0,0\n");
  expect_input_error(dir, {"gnss.csv", 3, "x", "expected a number, got '1.0.0'"});
}

TEST(LogReaderRejects, EmptyField) {
  const TempLogDir dir;
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks\n0,0,0\n1,,48\n");
  expect_input_error(dir, {"wheels.csv", 3, "rl_ticks", "empty field"});
}

TEST(LogReaderRejects, NaN) {
  const TempLogDir dir;
  dir.write("gnss.csv", "t,x,y\n0,0,0\n1,NaN,0\n");
  expect_input_error(dir, {"gnss.csv", 3, "x", "finite"});
}

TEST(LogReaderRejects, Infinity) {
  const TempLogDir dir;
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks\n0,0,0\n1,inf,48\n");
  expect_input_error(dir, {"wheels.csv", 3, "rl_ticks", "finite"});
}

TEST(LogReaderRejects, WrongFieldCount) {
  const TempLogDir dir;
  dir.write("gnss.csv", "t,x,y\n0,0,0\n1,1\n");
  expect_input_error(dir, {"gnss.csv", 3, "", "expected 3 fields"});
}

TEST(LogReaderRejects, NonIncreasingTime) {
  const TempLogDir dir;
  dir.write("gnss.csv", "t,x,y\n0,0,0\n2,0,0\n1,0,0\n");
  expect_input_error(dir, {"gnss.csv", 4, "t", "backwards"});
}

TEST(LogReaderRejects, DuplicatedTime) {
  const TempLogDir dir;
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks\n0,0,0\n1,48,48\n1,48,48\n");
  expect_input_error(dir, {"wheels.csv", 4, "t", "duplicated time 1 (also on line 3)"});
}

TEST(LogReaderRejects, NegativeTicksPerRev) {
  const TempLogDir dir;
  dir.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\n"
            "ticks_per_rev: -96\n");
  expect_input_error(dir, {"vehicle.yaml", 4, "ticks_per_rev", "-96 is out of range"});
}

TEST(LogReaderRejects, NonNumericVehicleValue) {
  const TempLogDir dir;
  dir.write("vehicle.yaml", "track_width_m: wide\ncircumference_rl_m: 2\ncircumference_rr_m: 2\n");
  expect_input_error(dir, {"vehicle.yaml", 1, "track_width_m", "expected a number, got 'wide'"});
}

TEST(LogReaderRejects, NaNInVehicleYaml) {
  const TempLogDir dir;
  dir.write("vehicle.yaml", "track_width_m: .nan\ncircumference_rl_m: 2\ncircumference_rr_m: 2\n");
  expect_input_error(dir, {"vehicle.yaml", 1, "track_width_m", "finite"});
}

TEST(LogReaderRejects, VehicleIdWithSpacesOrSlashes) {
  const TempLogDir dir;
  dir.write(
      "vehicle.yaml",
      "vehicle_id: car/1\ntrack_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\n");
  expect_input_error(dir, {"vehicle.yaml", 1, "vehicle_id", "letters, digits"});
}

TEST(LogReaderRejects, UnknownVehicleKey) {
  const TempLogDir dir;
  dir.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\n"
            "ticks_per_rev: 96\ntrackwidth: 1.5\n");
  expect_input_error(dir, {"vehicle.yaml", 5, "trackwidth", "unknown key"});
}

TEST(LogReaderRejects, InvalidYaml) {
  const TempLogDir dir;
  dir.write("vehicle.yaml", "track_width_m: [1.6\n");
  expect_input_error(dir, {"vehicle.yaml", 2, "", "not valid YAML"});
}

TEST(LogReaderRejects, ImplausibleCounterJump) {
  const TempLogDir dir;
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks\n0,0,0\n1,48,48\n2,30000,96\n");
  expect_input_error(dir, {"wheels.csv", 4, "rl_ticks", "neither plausible motion"});
}

TEST(LogReaderRejects, ImplausibleJumpEvenWithWrap) {
  const TempLogDir dir;
  dir.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\nticks_per_rev: 96\n"
            "counter_bits: 16\n");
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks\n0,0,0\n1,20000,48\n");
  expect_input_error(dir, {"wheels.csv", 3, "rl_ticks", "nor a wrap of the 16-bit counter"});
}

TEST(LogReaderRejects, TickOutsideCounterRange) {
  const TempLogDir dir;
  dir.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\nticks_per_rev: 96\n"
            "counter_bits: 8\n");
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks\n0,0,0\n1,300,48\n");
  expect_input_error(dir, {"wheels.csv", 3, "rl_ticks", "8-bit counter"});
}

TEST(LogReaderRejects, FractionalTicks) {
  const TempLogDir dir;
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks\n0,0,0\n1,47.5,48\n");
  expect_input_error(dir, {"wheels.csv", 3, "rl_ticks", "integer tick count"});
}

TEST(LogReaderRejects, ImplausibleWheelSpeed) {
  const TempLogDir dir;
  dir.write("wheels.csv", "t,rl_mps,rr_mps\n0,1,1\n1,1e6,1\n");
  expect_input_error(dir, {"wheels.csv", 3, "rl_mps", "implausible wheel speed"});
}

TEST(LogReaderRejects, LatitudeOutOfRange) {
  const TempLogDir dir;
  dir.write("gnss.csv", "t,lat,lon\n0,49,8\n1,91,8\n");
  expect_input_error(dir, {"gnss.csv", 3, "lat", "out of range"});
}

// --- empty and too-short streams ------------------------------------------------------------

TEST(LogReaderRejects, EmptyFile) {
  const TempLogDir dir;
  dir.write("gnss.csv", "");
  expect_input_error(dir, {"gnss.csv", 0, "", "empty"});
}

TEST(LogReaderRejects, EmptyStream) {
  const TempLogDir dir;
  dir.write("gnss.csv", "t,x,y\n");
  expect_input_error(dir, {"gnss.csv", 0, "", "empty stream"});
}

TEST(LogReaderRejects, WheelSpanTooShort) {
  const TempLogDir dir;
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks\n0,0,0\n");
  expect_input_error(dir, {"wheels.csv", 0, "", "time span too short"});
}

TEST(LogReaderRejects, StreamOutsideTheWheelTimeSpan) {
  const TempLogDir dir;
  dir.write("imu.csv", "t,ax,ay,wz\n100,0,0,0\n101,0,0,0\n");
  expect_input_error(dir, {"imu.csv", 0, "t", "no sample inside the wheel time span"});
}

}  // namespace
}  // namespace odocal

namespace odocal {
namespace {

TEST(VehicleConfigIo, WriteThenReadRoundTrips) {
  const TempLogDir dir;
  VehicleConfig vehicle;
  vehicle.track_width_m = 1.58;
  vehicle.circumference_rl_m = 1.964123456789;
  vehicle.circumference_rr_m = 1.96;
  vehicle.ticks_per_rev = 96;
  vehicle.counter_bits = 16;
  vehicle.wheelbase_m = 2.7;
  vehicle.vehicle_id = "van-07.b";
  vehicle.tyre_model = TyreModel{-3e-6, 5e-5, 0.0114, 0.0067, -0.04};
  vehicle.tyre_model->k_drive_slip = 0.05;
  vehicle.body.cg_height_m = 0.62;
  vehicle.body.rear_axle_load_share = 0.41;
  vehicle.body.drivetrain = Drivetrain::kFront;
  vehicle.body.friction = 0.8;
  vehicle.body.slip_curve_shape = 1.5;
  vehicle.body.brake_rear_share = 0.3;
  vehicle.body.all_wheel_drive_rear_share = 0.5;
  write_vehicle_config(vehicle, dir.file("vehicle.yaml"));
  const VehicleConfig read = read_vehicle_config(dir.file("vehicle.yaml"));
  EXPECT_EQ(read.vehicle_id, "van-07.b");
  EXPECT_DOUBLE_EQ(read.track_width_m, 1.58);
  EXPECT_NEAR(read.circumference_rl_m, 1.964123456789, 1e-11);
  EXPECT_EQ(read.ticks_per_rev, 96.0);
  EXPECT_EQ(read.counter_bits, 16);
  EXPECT_EQ(read.wheelbase_m, 2.7);
  EXPECT_FALSE(read.circumference_fl_m.has_value());
  ASSERT_TRUE(read.tyre_model.has_value());
  EXPECT_EQ(read.tyre_model->coefficients(), vehicle.tyre_model->coefficients());
  EXPECT_EQ(read.body.cg_height_m, 0.62);
  EXPECT_EQ(read.body.rear_axle_load_share, 0.41);
  EXPECT_EQ(read.body.mass_kg, VehicleBody{}.mass_kg);
  EXPECT_EQ(read.body.drivetrain, Drivetrain::kFront);
  EXPECT_EQ(read.body.friction, 0.8);  // the slip curve's
  EXPECT_EQ(read.body.slip_curve_shape, 1.5);
  EXPECT_EQ(read.body.brake_rear_share, 0.3);
  EXPECT_EQ(read.body.all_wheel_drive_rear_share, 0.5);
  // The physical terms' geometry: the vehicle's own wheelbase and rear track.
  EXPECT_EQ(read.body_geometry().wheelbase_m, 2.7);
  EXPECT_EQ(read.body_geometry().track_width_m, 1.58);
}

// The three required keys alone: a 1.6 m track and 2 m circumferences.
VehicleConfig plain_vehicle() {
  VehicleConfig vehicle;
  vehicle.track_width_m = 1.6;
  vehicle.circumference_rl_m = vehicle.circumference_rr_m = 2.0;
  return vehicle;
}

TEST(VehicleConfigIo, NoBodyKeyWhenTheBodyIsTheDefault) {
  const TempLogDir dir;
  VehicleConfig vehicle = plain_vehicle();
  write_vehicle_config(vehicle, dir.file("vehicle.yaml"));
  std::ifstream written(dir.file("vehicle.yaml"));
  const std::string text((std::istreambuf_iterator<char>(written)), {});
  EXPECT_NE(text.find("track_width_m"), std::string::npos);
  EXPECT_EQ(text.find("body"), std::string::npos);
  EXPECT_FALSE(read_vehicle_config(dir.file("vehicle.yaml")).body.drivetrain.has_value());
}

TEST(VehicleConfigIo, ADrivetrainAloneIsStatedWithoutTheBodysNumbers) {
  const TempLogDir dir;
  VehicleConfig vehicle = plain_vehicle();
  vehicle.body.drivetrain = Drivetrain::kAll;
  write_vehicle_config(vehicle, dir.file("vehicle.yaml"));
  std::ifstream written(dir.file("vehicle.yaml"));
  const std::string text((std::istreambuf_iterator<char>(written)), {});
  EXPECT_NE(text.find("drivetrain: all"), std::string::npos) << text;
  EXPECT_EQ(text.find("mass_kg"), std::string::npos) << text;
  EXPECT_EQ(read_vehicle_config(dir.file("vehicle.yaml")).body.drivetrain, Drivetrain::kAll);
}

TEST(VehicleConfigIo, TheImusMountingIsWrittenWhereStatedAndReadBack) {
  const TempLogDir dir;
  VehicleConfig vehicle = plain_vehicle();
  write_vehicle_config(vehicle, dir.file("vehicle.yaml"));
  EXPECT_EQ(testing::read_text_file(dir.file("vehicle.yaml")).find("imu_"), std::string::npos);
  vehicle.imu_position_m = Eigen::Vector2d(1.45, -0.2);
  write_vehicle_config(vehicle, dir.file("vehicle.yaml"));
  const VehicleConfig back = read_vehicle_config(dir.file("vehicle.yaml"));
  ASSERT_TRUE(back.imu_position_m);
  EXPECT_EQ(back.imu_position_m->x(), 1.45);
  EXPECT_EQ(back.imu_position_m->y(), -0.2);
  // One key states the place, the other taken as 0.
  const TempLogDir one;
  one.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\nimu_y_m: 0.3\n");
  const VehicleConfig left = read_vehicle_config(one.file("vehicle.yaml"));
  ASSERT_TRUE(left.imu_position_m);
  EXPECT_EQ(*left.imu_position_m, Eigen::Vector2d(0.0, 0.3));
}

TEST(VehicleConfigIo, TheAntennasMountingIsWrittenWhereStatedAndReadBack) {
  const TempLogDir dir;
  VehicleConfig vehicle = plain_vehicle();
  write_vehicle_config(vehicle, dir.file("vehicle.yaml"));
  EXPECT_EQ(testing::read_text_file(dir.file("vehicle.yaml")).find("gnss_"), std::string::npos);
  EXPECT_FALSE(read_vehicle_config(dir.file("vehicle.yaml")).gnss_position_m);
  vehicle.gnss_position_m = Eigen::Vector2d(1.5, -0.4);
  write_vehicle_config(vehicle, dir.file("vehicle.yaml"));
  const VehicleConfig back = read_vehicle_config(dir.file("vehicle.yaml"));
  ASSERT_TRUE(back.gnss_position_m);
  EXPECT_EQ(*back.gnss_position_m, Eigen::Vector2d(1.5, -0.4));
  EXPECT_FALSE(back.imu_position_m);
  const TempLogDir one;
  one.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\ngnss_x_m: 0.8\n");
  EXPECT_EQ(*read_vehicle_config(one.file("vehicle.yaml")).gnss_position_m,
            Eigen::Vector2d(0.8, 0.0));
  one.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\ngnss_y_m: left\n");
  expect_input_error(one, {"vehicle.yaml", 4, "gnss_y_m", ""});
}

TEST(LogReaderRejects, ImuMountedOffAnyVehicle) {
  const TempLogDir dir;
  dir.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\nimu_x_m: 145\n");
  expect_input_error(dir, {"vehicle.yaml", 4, "imu_x_m", "out of range"});
}

TEST(LogReaderRejects, BodyBeyondAnyVehicle) {
  const TempLogDir dir;
  dir.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\n"
            "body:\n  mass_kg: 1400\n  rear_axle_load_share: 1.4\n");
  expect_input_error(dir, {"vehicle.yaml", 6, "body.rear_axle_load_share", "0.95"});
  dir.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\n"
            "body:\n  wheelbase_m: 2.7\n");
  expect_input_error(dir, {"vehicle.yaml", 5, "body.wheelbase_m", "unknown"});
  dir.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\n"
            "body:\n  mass_kg: 1400\n  drivetrain: 4wd\n");
  expect_input_error(dir, {"vehicle.yaml", 6, "body.drivetrain", "rear, front or all"});
  dir.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\n"
            "body:\n  friction: 1\n  slip_curve_shape: 0.5\n");
  expect_input_error(dir, {"vehicle.yaml", 6, "body.slip_curve_shape", "out of range"});
}

TEST(LogReaderRejects, TyreCoefficientBeyondAnyTyre) {
  const TempLogDir dir;
  dir.write("vehicle.yaml",
            "track_width_m: 1.6\ncircumference_rl_m: 2\ncircumference_rr_m: 2\n"
            "tyre_model:\n  k_drive_s2pm: 0.01\n  k_lateral_s2pm: 3\n");
  expect_input_error(dir, {"vehicle.yaml", 6, "tyre_model.k_lateral_s2pm", "-0.01"});
}

}  // namespace
}  // namespace odocal
