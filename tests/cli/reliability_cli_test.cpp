// Hostile input end to end (issue 20's campaign, kept as regression tests): bounded simulations,
// whole-or-nothing log directories, one printable line per error, no absurd number with exit 0.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../support/run_cli.hpp"
#include "../support/temp_log_dir.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/io/log_reader.hpp"

namespace odocal {
namespace {

namespace fs = std::filesystem;
using testing::read_text_file;
using testing::run_cli;
using testing::TempLogDir;

std::size_t lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(ReliabilityCli, OversizedSimulationsAreRefusedAtOnce) {
  const TempLogDir dir;
  dir.write("stop.yaml",
            "route:\n  segments:\n    - straight: 100\n    - {arc: {radius_m: 10, turn_deg: 180}}\n"
            "    - {straight: 100, stop_s: 1e9}\n    - {arc: {radius_m: 10, turn_deg: 180}}\n");
  dir.write("long.yaml",
            "route:\n  laps: 1000\n  repeat: 1000\n  segments:\n    - straight: 100\n"
            "    - {arc: {radius_m: 10, turn_deg: 360}}\n");
  dir.write("blind.yaml",
            "route:\n  segments:\n    - straight: 100\n    - {arc: {radius_m: 10, turn_deg: 360}}\n"
            "sensors:\n  gnss:\n    outages:\n      - {start_s: 0, duration_s: 1e6}\n");
  for (const auto& [file, reason] :
       {std::pair{"stop.yaml", "at most 100 h"}, std::pair{"long.yaml", "at most 5000 km"},
        std::pair{"blind.yaml", "fewer than 2 GNSS fixes"}}) {
    const auto run = run_cli("simulate --scenario " + dir.file(file) + " --out " + dir.file("o"));
    EXPECT_EQ(run.status, 2) << file << ": " << run.err;
    EXPECT_NE(run.err.find(reason), std::string::npos) << run.err;
    EXPECT_FALSE(fs::exists(dir.file("o"))) << file;
  }
  // A typo vertex kilometres off the centreline, and a circle of radius 1e300 (was SIGSEGV).
  std::ostringstream typo, huge;
  typo << "# x_m,y_m,w_tr_right_m,w_tr_left_m\n";
  huge << "# x_m,y_m,w_tr_right_m,w_tr_left_m\n";
  for (int i = 0; i < 40; ++i) {
    const double a = 2 * M_PI * i / 40;
    typo << (i == 7 ? 3.5e6 : 200 * std::cos(a)) << "," << 200 * std::sin(a) << ",5,5\n";
    huge << 1e300 * std::cos(a) << "," << 1e300 * std::sin(a) << ",5,5\n";
  }
  dir.write("typo.csv", typo.str());
  dir.write("huge.csv", huge.str());
  const auto run_typo =
      run_cli("simulate --ideal --track " + dir.file("typo.csv") + " --out " + dir.file("o"));
  EXPECT_EQ(run_typo.status, 2);
  EXPECT_NE(run_typo.err.find("typo.csv:9: 'x_m'"), std::string::npos) << run_typo.err;
  EXPECT_EQ(run_cli("simulate --ideal --track " + dir.file("huge.csv") + " --out " + dir.file("o"))
                .status,
            2);
}

TEST(ReliabilityCli, AnImportReplacesAWholeLogOrLeavesItAsItWas) {
  const TempLogDir src, out;
  src.write("w.csv", "t,l,r\n0,0,0\n1,48,48\n2,96,96\n3,144,144\n");
  src.write("g.csv", "t,e,n\n0,0,0\n1,1,0\n2,2,0\n3,3,0\n");
  const std::string streams =
      "  wheels: {file: w.csv, time: {column: t, unit: s}, rl: {column: l, unit: ticks},"
      " rr: {column: r, unit: ticks}}\n"
      "  gnss: {file: g.csv, time: {column: t, unit: s}, position: local,"
      " x: {column: e, unit: m}, y: {column: n, unit: m}}\n";
  src.write("map.yaml",
            "vehicle: {track_width_m: 1.6, circumference_rl_m: 2, circumference_rr_m: 2, "
            "ticks_per_rev: 96}\nstreams:\n" +
                streams);
  // The target is an old log with a stream the new one does not have, and a note of the user's.
  const std::string log = out.path().string();
  out.write("imu.csv", "t,ax,ay,wz\n0,0,0,0\n");
  out.write("notes.txt", "mine\n");
  const auto run = run_cli("import csv --map " + src.file("map.yaml") + " --out " + log);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_FALSE(fs::exists(out.file("imu.csv")));  // stale: not part of the new log
  EXPECT_EQ(read_text_file(out.file("notes.txt")), "mine\n");
  const std::string gnss_before = read_text_file(out.file("gnss.csv"));

  // A map whose converted log does not read back (time in ms makes 3 ms of wheels against 3 s
  // of GNSS... here: a wheel column that overflows after the unit conversion).
  src.write("bad.csv", "t,l,r\n0,0,0\n1,1e308,48\n2,96,96\n3,144,144\n");
  src.write("bad.yaml",
            "vehicle: {track_width_m: 1.6, circumference_rl_m: 2, circumference_rr_m: 2}\n"
            "streams:\n  wheels: {file: bad.csv, time: {column: t, unit: s}, rl: {column: l, "
            "unit: rev}, rr: {column: r, unit: rev}}\n"
            "  gnss: {file: g.csv, time: {column: t, unit: s}, position: local,"
            " x: {column: e, unit: m}, y: {column: n, unit: m}}\n");
  const auto bad = run_cli("import csv --map " + src.file("bad.yaml") + " --out " + log);
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("bad.csv:3: 'l'"), std::string::npos) << bad.err;
  EXPECT_EQ(read_text_file(out.file("gnss.csv")), gnss_before);
  for (const auto& entry : fs::directory_iterator(out.path().parent_path())) {
    EXPECT_FALSE(entry.path().filename().string().starts_with("." + out.path().filename().string()))
        << "staging directory left behind: " << entry.path();
  }
}

TEST(ReliabilityCli, TheLogsOwnVehicleFileIsNotAnOutput) {
  const TempLogDir dir;
  ASSERT_EQ(run_cli("simulate --ideal --laps 1 --scenario parking --out " + dir.file("log")).status,
            0);
  const std::string vehicle = read_text_file(dir.file("log/vehicle.yaml"));
  const auto run =
      run_cli("calibrate " + dir.file("log") + " --vehicle-out " + dir.file("log/vehicle.yaml"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("the log's own vehicle.yaml"), std::string::npos) << run.err;
  EXPECT_EQ(read_text_file(dir.file("log/vehicle.yaml")), vehicle);
}

TEST(ReliabilityCli, ErrorsAreOnePrintableLine) {
  const TempLogDir dir;
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks\n0,0,0\n1,a\x1b[31m\rb,3\n");
  const auto run = run_cli("calibrate " + dir.path().string());
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(lines(run.err), 1u) << run.err;
  EXPECT_NE(run.err.find("a\\x1b[31m\\x0db"), std::string::npos) << run.err;
  const auto usage = run_cli("calibrate --no-such-flag");
  EXPECT_EQ(usage.status, 2);
  EXPECT_EQ(lines(usage.err), 1u) << usage.err;
}

// Wheels logged on after the GNSS stopped (a clock jump of 1e6 s in the middle, which gave
// c_RL = -3.6e9 m with exit 0): only the span both streams cover is used, and the estimate is
// as good as on that span alone.
TEST(ReliabilityCli, WheelsBeyondTheGnssSpanAreCutOff) {
  const TempLogDir dir;
  ASSERT_EQ(run_cli("simulate --ideal --laps 1 --out " + dir.file("log")).status, 0);
  std::ifstream in(dir.file("log/wheels.csv"));
  std::ostringstream shifted;
  std::string line;
  std::getline(in, line);
  shifted << line << "\n";
  for (int row = 0; std::getline(in, line); ++row) {
    const auto comma = line.find(',');
    const double t = std::stod(line.substr(0, comma));
    shifted << fmt::format("{:.4f}", row > 5000 ? t + 1e6 : t) << line.substr(comma) << "\n";
  }
  in.close();
  dir.write("log/wheels.csv", shifted.str());
  LogReadOptions options;
  options.read_truth = false;
  const Log log = read_log(dir.file("log"), options);
  const CalibrationSummary summary = core(calibrate(log, CalibrationConfig{}));
  ASSERT_TRUE(summary.usable()) << summary.message;
  EXPECT_NE(summary.preparation.describe().find("outside the GNSS span cut off"),
            std::string::npos);
  const std::string truth_yaml = read_text_file(dir.file("log/truth.yaml"));
  const std::string key = "circumference_rl_m: ";
  const double truth = std::stod(truth_yaml.substr(truth_yaml.find(key) + key.size()));
  EXPECT_LT(std::abs(summary.estimate.circumference_rl_m - truth), 3 * summary.sigma_rl_m());
}

}  // namespace
}  // namespace odocal
