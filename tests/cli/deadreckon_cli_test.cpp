// `odocal deadreckon` end to end: reports, exports and exit statuses.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "../support/run_cli.hpp"
#include "../support/temp_log_dir.hpp"

namespace odocal {
namespace {

using testing::read_text_file;
using testing::run_cli;
using testing::TempLogDir;

TEST(DeadreckonCli, ReportsErrorsAgainstGnssOnTheBaselineLog) {
  const TempLogDir dir;
  const auto run = run_cli("deadreckon " + dir.path().string() + " --start gnss");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("reference    gnss.csv (4 position samples)"), std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("position     mean 0.000 m, max 0.000 m"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("no heading reference"), std::string::npos) << run.out;
}

TEST(DeadreckonCli, OverridesCircumferencesAndUsesTruth) {
  const TempLogDir dir;
  dir.write("truth.csv", "t,x,y,heading\n0,0,0,0\n3,3,0,0\n");
  // 10 % larger wheels: 3.3 m instead of 3 m after 3 s.
  const auto run = run_cli("deadreckon " + dir.path().string() +
                           " --circumference-rl 2.2 --circumference-rr 2.2");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("from truth"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("max 0.300 m"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("final drift  0.300 m = 9.091 % of 3.3 m"), std::string::npos) << run.out;
}

TEST(DeadreckonCli, WritesCsvAndTumTrajectories) {
  const TempLogDir dir;
  dir.write("gnss.csv", "t,x,y\n0,0,0\n1,0,1\n2,0,2\n3,0,3\n");  // GNSS says: going north
  const std::string csv = dir.file("traj.csv");
  const std::string tum = dir.file("traj.tum");
  const auto run =
      run_cli("deadreckon " + dir.path().string() + " --start gnss --out " + csv + " --tum " + tum);
  ASSERT_EQ(run.status, 0) << run.err;
  const std::string csv_text = read_text_file(csv);
  EXPECT_EQ(csv_text.substr(0, 14), "t,x,y,heading\n");
  // The start aligned to GNSS heads north: after 3 s the vehicle is 3 m north of the start.
  std::istringstream tum_lines(read_text_file(tum));
  std::string line, last;
  int count = 0;
  while (std::getline(tum_lines, line)) {
    last = line;
    ++count;
  }
  EXPECT_EQ(count, 4);
  double t, x, y, z, qx, qy, qz, qw;
  std::istringstream(last) >> t >> x >> y >> z >> qx >> qy >> qz >> qw;
  EXPECT_DOUBLE_EQ(t, 3.0);
  EXPECT_NEAR(x, 0.0, 1e-5);
  EXPECT_NEAR(y, 3.0, 1e-5);
  EXPECT_NEAR(qz, std::sqrt(0.5), 1e-8);
  EXPECT_NEAR(qw, std::sqrt(0.5), 1e-8);
}

TEST(DeadreckonCli, BadInputExitsWithStatusTwoAndOneLine) {
  const TempLogDir dir;
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks\n0,0,0\n1,nan,48\n");
  const auto run = run_cli("deadreckon " + dir.path().string());
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.err, "odocal: error: " + dir.file("wheels.csv") +
                         ":3: 'rl_ticks': expected a finite number, got 'nan'\n");
}

TEST(DeadreckonCli, MissingLogDirectoryExitsWithStatusTwo) {
  const auto run = run_cli("deadreckon /nonexistent/odocal-log");
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("log directory does not exist"), std::string::npos) << run.err;
}

TEST(DeadreckonCli, NoStartHeadingExitsWithStatusThree) {
  const TempLogDir dir;
  dir.write("gnss.csv", "t,x,y\n0,0,0\n3,0,0\n");  // GNSS sees no motion, no heading.csv
  const auto run = run_cli("deadreckon " + dir.path().string() + " --start gnss");
  EXPECT_EQ(run.status, 3) << run.err;
  EXPECT_NE(run.err.find("no start heading"), std::string::npos) << run.err;
}

// The mean heading error that `deadreckon` reports ("heading      mean X deg, ...").
double mean_heading_deg(const std::string& report) {
  const std::size_t at = report.find("heading      mean ");
  if (at == std::string::npos) return NAN;
  return std::stod(report.substr(at + 18));
}

// A log that starts in motion, straight east at 12.9 m/s (12.38 ticks a sample at 50 Hz), its
// encoders one at 0.05 of a tick and the other at 0.9: the raw counts are a tick apart most of the
// time, a heading of 0.63 deg on average; the averaged counts are not.
TEST(DeadreckonCli, AveragedTickCountsKeepAStraightStraight) {
  const TempLogDir dir;
  std::ostringstream wheels, truth, gnss;
  wheels << "t,rl_ticks,rr_ticks\n";
  truth << "t,x,y,heading\n";
  gnss << "t,x,y\n";
  const double speed = 12.896, ticks_per_m = 96.0 / 2.0;
  for (int k = 0; k <= 1000; ++k) {
    const double t = k / 50.0, x = speed * t;
    wheels << t << "," << std::floor(0.05 + x * ticks_per_m) << ","
           << std::floor(0.9 + x * ticks_per_m) << "\n";
    truth << t << "," << x << ",0,0\n";
    if (k % 50 == 0) gnss << t << "," << x << ",0\n";
  }
  dir.write("wheels.csv", wheels.str());
  dir.write("truth.csv", truth.str());
  dir.write("gnss.csv", gnss.str());
  const auto averaged = run_cli("deadreckon " + dir.path().string());
  const auto raw = run_cli("deadreckon " + dir.path().string() + " --tick-smoothing 0");
  ASSERT_EQ(averaged.status, 0) << averaged.err;
  ASSERT_EQ(raw.status, 0) << raw.err;
  EXPECT_GT(mean_heading_deg(raw.out), 0.5) << raw.out;
  EXPECT_LT(mean_heading_deg(averaged.out), 0.15) << averaged.out;
}

TEST(DeadreckonCli, UsageErrorsExitWithStatusTwo) {
  EXPECT_EQ(run_cli("deadreckon").status, 2);
  EXPECT_EQ(run_cli("deadreckon some-log --start sideways").status, 2);
  EXPECT_EQ(run_cli("deadreckon some-log --tick-smoothing -1").status, 2);
  EXPECT_EQ(run_cli("deadreckon some-log --tick-smoothing nan").status, 2);
  EXPECT_EQ(run_cli("--help").status, 0);
}

}  // namespace
}  // namespace odocal

namespace odocal {
namespace {

// A log that starts with the car standing for a minute, without heading.csv: deadreckon starts
// at the first motion (it once refused: "no start heading ... the vehicle barely moves"), and
// --from / --to pick a window.
TEST(DeadreckonCli, StartsAtTheFirstMotionAndTakesAWindow) {
  const testing::TempLogDir dir;
  dir.write("standing.yaml",
            "driver: {start_dwell_s: 60}\nroute:\n  segments:\n    - straight: 300\n"
            "    - arc: {radius_m: 30, turn_deg: 90}\n    - straight: 300\n");
  const std::string log = dir.file("log");
  ASSERT_EQ(
      testing::run_cli("simulate --ideal --scenario " + dir.file("standing.yaml") + " --out " + log)
          .status,
      0);
  std::filesystem::remove(log + "/heading.csv");
  std::filesystem::remove(log + "/truth.csv");
  const auto run = testing::run_cli("deadreckon " + log + " --start gnss");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("(first motion)"), std::string::npos) << run.out;
  const auto window = testing::run_cli("deadreckon " + log + " --start gnss --from 65 --to 110");
  ASSERT_EQ(window.status, 0) << window.err;
  EXPECT_NE(window.out.find(", 45.0 s,"), std::string::npos) << window.out;
  const auto empty = testing::run_cli("deadreckon " + log + " --from 1e6");
  EXPECT_EQ(empty.status, 3) << empty.err;
  EXPECT_NE(empty.err.find("the window 1000000 s to inf s holds 0 wheel samples"),
            std::string::npos)
      << empty.err;
}

}  // namespace
}  // namespace odocal
