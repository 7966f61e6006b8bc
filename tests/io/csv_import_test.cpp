// The CSV importer against a synthetic logger with known truth (a constant-radius left turn),
// through the documented example map examples/ticks-logger/map.yaml; and its error messages.

#include "odocal/io/csv_import.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "../support/temp_log_dir.hpp"
#include "odocal/error.hpp"
#include "odocal/io/log_reader.hpp"
#include "odocal/model/angle.hpp"

namespace odocal {
namespace {

using testing::TempLogDir;
constexpr double kPi = std::numbers::pi;
const std::string kMap = std::string(ODOCAL_SOURCE_DIR) + "/examples/ticks-logger/map.yaml";

// 20 s of a 30 m-radius left turn at 6 m/s, heading east at the start, written the way the
// ticks logger would: ns stamps, 16-bit tick counters, g and deg/s, compass degrees.
void write_logger_files(const TempLogDir& dir) {
  const double radius = 30.0, speed = 6.0, track = 1.58, c = 1.98, rate = speed / radius;
  const std::int64_t t0_ns = 1'700'000'000'000'000'000;
  std::string encoders = "stamp_ns,rear_left_count,rear_right_count\n";
  std::string accel = "stamp_ns,acc_x,acc_y,acc_z\n", gyro = "stamp_ns,rate_z_dps\n";
  std::string gps = "stamp_ns,latitude,longitude,h_accuracy,ground_speed_kmh\n",
              compass = "stamp_ns,heading_deg\n";
  for (int k = 0; k <= 1000; ++k) {  // 50 Hz
    const double t = 0.02 * k;
    const std::int64_t ns = t0_ns + static_cast<std::int64_t>(k) * 20'000'000;
    const double angle = rate * t;
    encoders += fmt::format(
        "{},{},{}\n", ns,
        (65000 + static_cast<long>(std::floor((radius - track / 2) * angle / c * 96))) % 65536,
        static_cast<long>(std::floor((radius + track / 2) * angle / c * 96)) % 65536);
    // FRD: the centripetal acceleration of a left turn points left = -y; yaw rate CCW = -z.
    accel += fmt::format("{},0.0,{:.6f},1.0\n", ns, -speed * rate / 9.80665);
    if (k % 2 == 0)
      gyro += fmt::format("{},{:.6f}\n", ns + 5'000'000, -rate * 180 / kPi);  // own clock ticks
    if (k % 5 == 0) {
      const double x = radius * std::sin(angle), y = radius * (1 - std::cos(angle));
      gps += fmt::format("{},{:.9f},{:.9f},1.5,{:.4f}\n", ns, 49.0 + y / 111'200.0,
                         8.0 + x / 72'950.0, speed * 3.6);
      compass += fmt::format("{},{:.4f}\n", ns, std::fmod(90.0 - angle * 180 / kPi + 360.0, 360.0));
    }
  }
  dir.write("encoders.csv", encoders);
  dir.write("accel.csv", accel);
  dir.write("gyro.csv", gyro);
  dir.write("gps.csv", gps);
  dir.write("compass.csv", compass);
}

TEST(CsvImport, ConvertsUnitsFramesConventionsAndFiles) {
  const TempLogDir src;
  write_logger_files(src);
  const TempLogDir out;
  const ImportSummary summary = import_csv(kMap, src.path(), out.path());
  const Log log = read_log(out.path());
  // Ticks with a wrapping counter become the rolled distance: 20 s at 6 m/s.
  EXPECT_NEAR(summary.wheel_distance_m, 120.0, 0.1);
  EXPECT_NEAR(log.wheels.t_s.front(), 1.7e9, 1.0);  // ns -> s
  ASSERT_TRUE(log.imu && log.heading);
  const double rate = 6.0 / 30.0;
  // FRD -> FLU: the left turn's centripetal acceleration and yaw rate come out positive; g ->
  // m/s^2.
  EXPECT_NEAR(log.imu->ay_mps2[10], 6.0 * rate, 1e-5);
  EXPECT_NEAR(log.imu->wz_radps[10], rate, 1e-5);  // gyro.csv resampled onto accel.csv's stamps
  // Compass 90 deg (east) -> 0 rad ENU; 20 s later the turn has added 4 rad.
  EXPECT_NEAR(log.heading->heading_rad.front(), 0.0, 1e-6);
  EXPECT_NEAR(log.heading->heading_rad.back(), wrap_angle(4.0), 1e-6);
  EXPECT_NEAR(log.gnss.speed_mps.front(), 6.0, 1e-6);  // km/h -> m/s
  EXPECT_DOUBLE_EQ(log.gnss.sigma_m.front(), 1.5);
  ASSERT_EQ(summary.streams.size(), 4u);
  // Epoch nanoseconds as doubles keep ~0.25 us: rates to within 1e-3 Hz.
  EXPECT_NEAR(summary.streams[0].median_rate_hz, 50.0, 1e-3);
  EXPECT_NEAR(summary.streams[1].median_rate_hz, 10.0, 1e-3);
}

// An encoder that counts backwards (the right one, on a wrapping 16-bit counter) is read as it
// is with `scale: -1` in the map, the fix `odocal doctor` names: the same log as the forward one.
TEST(CsvImport, ScaleMinusOneReadsAReversedWrappingCounter) {
  const TempLogDir src;
  write_logger_files(src);
  const TempLogDir forward;
  import_csv(kMap, src.path(), forward.path());
  std::ifstream encoders_in(src.file("encoders.csv"));
  std::string line, reversed;
  std::getline(encoders_in, line);
  reversed = line + "\n";
  while (std::getline(encoders_in, line)) {
    const auto comma = line.rfind(',');
    const long count = std::stol(line.substr(comma + 1));
    reversed += line.substr(0, comma + 1) + std::to_string((65536 - count) % 65536) + "\n";
  }
  src.write("encoders.csv", reversed);
  std::ifstream example(kMap);
  std::stringstream map;
  map << example.rdbuf();
  std::string text = map.str();
  const std::string rr = "column: rear_right_count, unit: ticks";
  ASSERT_NE(text.find(rr), std::string::npos);
  text.replace(text.find(rr), rr.size(), rr + ", scale: -1");
  src.write("map.yaml", text);
  const TempLogDir out;
  import_csv(src.file("map.yaml"), src.path(), out.path());
  const Log a = read_log(forward.path()), b = read_log(out.path());
  ASSERT_EQ(a.wheels.size(), b.wheels.size());
  for (std::size_t k = 0; k < a.wheels.size(); ++k)
    ASSERT_DOUBLE_EQ(a.wheels.rev_rr[k], b.wheels.rev_rr[k]) << k;
}

void expect_map_error(const std::string& map_text, const std::string& field,
                      const std::string& says) {
  const TempLogDir src;
  write_logger_files(src);
  std::ifstream example(kMap);
  std::stringstream base;
  base << example.rdbuf();
  std::string text = base.str();
  const auto [from, to] =
      std::pair(map_text.substr(0, map_text.find("=>")), map_text.substr(map_text.find("=>") + 2));
  ASSERT_NE(text.find(from), std::string::npos) << from;
  text.replace(text.find(from), from.size(), to);
  src.write("map.yaml", text);
  const TempLogDir out;
  try {
    import_csv(src.file("map.yaml"), src.path(), out.path());
    FAIL() << "expected an error about " << field;
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().field, field) << e.what();
    EXPECT_NE(e.problem().find(says), std::string::npos) << e.what();
  }
}

TEST(CsvImportRejects, UnknownUnit) {
  expect_map_error("unit: ticks}\n    rr=>unit: clicks}\n    rr", "streams.wheels.rl.unit",
                   "expected one of ticks");
}

TEST(CsvImportRejects, WrongKindOfUnit) {
  expect_map_error("{column: heading_deg, unit: deg}=>{column: heading_deg, unit: m/s}",
                   "streams.heading.heading.unit", "expected one of rad, deg, rev");
}

TEST(CsvImportRejects, MissingColumn) {
  expect_map_error("column: latitude,=>column: lat,", "streams.gnss.lat.column",
                   "column 'lat' is not in");
}

TEST(CsvImportRejects, UnknownKey) {
  expect_map_error("frame: frd=>frame: frd\n    axes: 3", "streams.imu.axes", "unknown key");
}

TEST(CsvImportRejects, ZeroScale) {
  expect_map_error("unit: ticks}\n    rr=>unit: ticks, scale: 0}\n    rr",
                   "streams.wheels.rl.scale", "must not be 0");
}

TEST(CsvImportRejects, BadFrame) {
  expect_map_error("frame: frd=>frame: nwu", "streams.imu.frame", "expected flu");
}

TEST(CsvImportRejects, NonIncreasingTimeNamesTheSourceFile) {
  const TempLogDir src;
  write_logger_files(src);
  src.write("compass.csv",
            "stamp_ns,heading_deg\n1700000000000000000,90\n1700000000000000000,90\n");
  const TempLogDir out;
  try {
    import_csv(kMap, src.path(), out.path());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().file, src.file("compass.csv")) << e.what();
    EXPECT_EQ(e.location().line, 3u);
    EXPECT_EQ(e.location().field, "stamp_ns");
  }
}

TEST(CsvImportRejects, MissingSourceFile) {
  const TempLogDir src;
  write_logger_files(src);
  src.remove("gyro.csv");
  const TempLogDir out;
  EXPECT_THROW(import_csv(kMap, src.path(), out.path()), InputError);
}

}  // namespace
}  // namespace odocal
