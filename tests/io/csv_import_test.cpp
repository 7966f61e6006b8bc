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

// The tyres' force from the car's bus, in kN at 25 Hz in a file of its own, onto the wheels'
// time base in newtons (wheels.csv's drive_force_n).
TEST(CsvImport, ReadsTheDriveForceInItsUnitOntoTheWheelsClock) {
  const TempLogDir src;
  write_logger_files(src);
  std::string torque = "stamp_ns,force_kn\n";
  for (int k = 0; k <= 500; ++k)  // 0.2 kN rising by 0.01 kN per second
    torque += fmt::format("{},{:.4f}\n", 1'700'000'000'000'000'000 + std::int64_t{k} * 40'000'000,
                          0.2 + 0.01 * 0.04 * k);
  src.write("torque.csv", torque);
  std::ifstream in(kMap);
  std::stringstream map;
  map << in.rdbuf();
  std::string text = map.str();
  const std::string rr = "    rr: {column: rear_right_count, unit: ticks}\n";
  text.replace(text.find(rr), rr.size(),
               rr + "    drive_force: {file: torque.csv, column: force_kn, unit: kN}\n");
  src.write("map.yaml", text);
  const TempLogDir out;
  import_csv(src.file("map.yaml"), src.path(), out.path());
  const Log log = read_log(out.path());
  ASSERT_EQ(log.wheels.drive_force_n.size(), log.wheels.size());
  // Row 100 is 2 s in: 0.22 kN.
  EXPECT_NEAR(log.wheels.drive_force_n[100], 220.0, 0.1);
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

// Loggers as they are: preamble lines, comments, trailing commas, garbage in a column nobody
// uses (kept) and in a used one (dropped and counted: a warning above 1 % of rows), a time scale,
// a column offset, and a column from another file on that file's own clock.
TEST(CsvImport, LoggerDialectBadValuesTimeScaleOffsetAndOwnClock) {
  const TempLogDir src;
  std::string wheels = "logger v2.1\nexported 2026-11-23\nticks,left,right,status,\n";
  std::string gnss = "sep=,\n# receiver A\nt_half_s,x,y,\n";
  std::string speed = "clock_ds,v_kmh\n";  // another file: deciseconds, 0.5 s ahead
  for (int k = 0; k <= 400; ++k) {         // 20 s at 20 Hz, 10 m/s straight east
    const double t = 0.05 * k;
    const std::string status = k == 7 ? "garbage" : "ok";
    wheels += fmt::format("{:.0f},{:.4f},{:.4f},{},\n", t * 1000.0, 36.0,
                          k == 100 ? -INFINITY : 36.0, status == "ok" ? "1" : "x");
    if (k % 4 == 0) gnss += fmt::format("{:.3f},{:.3f},{:.3f},\n", t / 2, 10.0 * t, 0.0);
    if (k % 2 == 0) speed += fmt::format("{:.1f},{:.3f}\n", (t + 0.5) * 10.0, 36.0);
  }
  src.write("wheels.csv", wheels);
  src.write("gps.csv", gnss);
  src.write("speed.csv", speed);
  src.write("map.yaml",
            R"(vehicle: {track_width_m: 1.6, circumference_rl_m: 1.96, circumference_rr_m: 1.96}
files:
  wheels.csv: {skip_lines: 2}
streams:
  wheels:
    file: wheels.csv
    bad_values: drop
    time: {column: ticks, unit: ms}
    rl: {column: left, unit: km/h}
    rr: {column: right, unit: km/h}
  gnss:
    file: gps.csv
    time: {column: t_half_s, unit: s, scale: 2}
    position: local
    x: {column: x, unit: m, offset: 5}
    y: {column: y, unit: m}
    speed: {file: speed.csv, column: v_kmh, unit: km/h, time: {column: clock_ds, unit: s, scale: 0.1, offset_s: -0.5}}
)");
  const TempLogDir out;
  const ImportSummary summary = import_csv(src.file("map.yaml"), src.path(), out.path());
  const Log log = read_log(out.path());
  EXPECT_EQ(log.wheels.size(), 400u);  // one row of 401 dropped: its right wheel is not finite
  ASSERT_EQ(summary.notes.size(), 1u);
  EXPECT_NE(summary.notes[0].find("wheels: 1 of 401 rows dropped"), std::string::npos)
      << summary.notes[0];
  EXPECT_NE(summary.notes[0].find("wheels.csv:104"), std::string::npos) << summary.notes[0];
  EXPECT_TRUE(summary.warnings.empty());
  EXPECT_NEAR(log.gnss.t_s.back(), 20.0, 1e-9);  // t_half_s x 2
  EXPECT_NEAR(log.gnss.x_m.front(), 5.0, 1e-9);  // the column's offset
  EXPECT_NEAR(log.gnss.x_m.back(), 205.0, 1e-6);
  ASSERT_EQ(log.gnss.speed_mps.size(), log.gnss.size());
  EXPECT_NEAR(log.gnss.speed_mps[3], 10.0, 1e-9);  // km/h on the other file's own clock
  EXPECT_NEAR(summary.wheel_distance_m, 200.0, 1.0);
}

TEST(CsvImport, ManyDroppedRowsWarn) {
  const TempLogDir src;
  std::string wheels = "t,left,right\n", gnss = "t,x,y\n";
  for (int k = 0; k <= 400; ++k) {
    const double t = 0.05 * k;
    wheels += fmt::format("{:.2f},{},{}\n", t, k % 20 == 3 ? "nan" : "10", "10");
    if (k % 4 == 0) gnss += fmt::format("{:.2f},{:.3f},0\n", t, 10.0 * t);
  }
  src.write("wheels.csv", wheels);
  src.write("gnss.csv", gnss);
  src.write("map.yaml",
            R"(vehicle: {track_width_m: 1.6, circumference_rl_m: 1.96, circumference_rr_m: 1.96}
streams:
  wheels: {file: wheels.csv, bad_values: drop, time: {column: t, unit: s}, rl: {column: left, unit: m/s}, rr: {column: right, unit: m/s}}
  gnss: {file: gnss.csv, time: {column: t, unit: s}, position: local, x: {column: x, unit: m}, y: {column: y, unit: m}}
)");
  const TempLogDir out;
  const ImportSummary summary = import_csv(src.file("map.yaml"), src.path(), out.path());
  ASSERT_EQ(summary.warnings.size(), 1u);
  EXPECT_NE(summary.warnings[0].find("wheels: 20 of 401 rows dropped (5.0 %"), std::string::npos)
      << summary.warnings[0];
  // Without bad_values: drop the first bad cell is an error naming it.
  src.write("map.yaml",
            R"(vehicle: {track_width_m: 1.6, circumference_rl_m: 1.96, circumference_rr_m: 1.96}
streams:
  wheels: {file: wheels.csv, time: {column: t, unit: s}, rl: {column: left, unit: m/s}, rr: {column: right, unit: m/s}}
  gnss: {file: gnss.csv, time: {column: t, unit: s}, position: local, x: {column: x, unit: m}, y: {column: y, unit: m}}
)");
  const TempLogDir out2;
  try {
    import_csv(src.file("map.yaml"), src.path(), out2.path());
    FAIL() << "expected an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().line, 5u) << e.what();
    EXPECT_EQ(e.location().field, "left") << e.what();
  }
}

// A logger longer than a chunk of rows (the importer reads 65 536 at a time): dedupe, the time
// order and another file's values carry across chunk boundaries, and the truth's course comes
// out of a path read piece by piece, standing stops included.
TEST(CsvImport, ALongLoggerStreamsThroughChunks) {
  const TempLogDir src;
  std::string wheels = "t,left,right\n", gnss = "t,x,y\n", speed = "clock,v\n", truth = "t,x,y\n";
  constexpr int kRows = 150'000;    // 25 minutes at 100 Hz
  const auto x_at = [](double t) {  // 10 m/s east, standing from 600 to 660 s
    return t < 600.0 ? 10.0 * t : t < 660.0 ? 6000.0 : 6000.0 + 10.0 * (t - 660.0);
  };
  for (int k = 0; k < kRows; ++k) {
    const double t = 0.01 * k;
    const double v = t >= 600.0 && t < 660.0 ? 0.0 : 10.0;
    wheels += fmt::format("{:.2f},{},{}\n", t, v, v);
    // A 10 Hz fix written on every 100 Hz row.
    const double fix_t = 0.1 * std::floor(t * 10.0 + 1e-9);
    gnss += fmt::format("{:.2f},{:.3f},0\n", t, x_at(fix_t));
    if (k % 3 == 0) speed += fmt::format("{:.3f},{}\n", t + 0.005, v);
    truth += fmt::format("{:.2f},{:.3f},0\n", t, x_at(t));
  }
  src.write("wheels.csv", wheels);
  src.write("gnss.csv", gnss);
  src.write("speed.csv", speed);
  src.write("truth.csv", truth);
  src.write("map.yaml",
            R"(vehicle: {track_width_m: 1.6, circumference_rl_m: 1.96, circumference_rr_m: 1.96}
streams:
  wheels: {file: wheels.csv, time: {column: t, unit: s}, rl: {column: left, unit: m/s}, rr: {column: right, unit: m/s}}
  gnss:
    file: gnss.csv
    time: {column: t, unit: s}
    dedupe: [x, y]
    position: local
    x: {column: x, unit: m}
    y: {column: y, unit: m}
    speed: {file: speed.csv, column: v, unit: m/s, time: {column: clock, unit: s}}
  truth: {file: truth.csv, time: {column: t, unit: s}, position: local, x: {column: x, unit: m}, y: {column: y, unit: m}}
)");
  const TempLogDir out;
  const ImportSummary summary = import_csv(src.file("map.yaml"), src.path(), out.path());
  const Log log = read_log(out.path());
  EXPECT_EQ(log.wheels.size(), static_cast<std::size_t>(kRows));
  // One row per fix while driving; standing, the fix repeats and collapses into one.
  const std::size_t fixes_driving = 14'400;
  EXPECT_NEAR(static_cast<double>(log.gnss.size()), static_cast<double>(fixes_driving + 1), 2.0);
  for (std::size_t k = 1; k < log.gnss.size(); ++k) {
    ASSERT_GT(log.gnss.t_s[k], log.gnss.t_s[k - 1]);
    // The other file's speed, interpolated across its own chunks: 10 m/s except near the stop.
    if (log.gnss.t_s[k] < 590.0 || log.gnss.t_s[k] > 670.0) {
      ASSERT_NEAR(log.gnss.speed_mps[k], 10.0, 1e-9) << log.gnss.t_s[k];
    }
  }
  ASSERT_TRUE(log.truth.has_value());
  // The course east everywhere, the standing rows included (0.5 m before and after the stop).
  EXPECT_GT(log.truth->size(), static_cast<std::size_t>(kRows) - 200);
  for (const Pose2& pose : log.truth->pose) ASSERT_NEAR(pose.z(), 0.0, 1e-9);
  EXPECT_NEAR(summary.wheel_distance_m, 14'400.0, 1.0);
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
