// `odocal simulate` end to end: a log that reads back, flags that override the scenario, and
// exit statuses for bad scenarios.

#include <gtest/gtest.h>

#include "../support/run_cli.hpp"
#include "../support/temp_log_dir.hpp"
#include "odocal/io/log_reader.hpp"

namespace odocal {
namespace {

using testing::read_text_file;
using testing::run_cli;
using testing::TempLogDir;

TEST(SimulateCli, WritesAReadableLogWithTruthAndEffectiveScenario) {
  const TempLogDir dir;
  const std::string out = dir.file("parking");
  const auto run = run_cli(
      "simulate --scenario parking --ideal --wear-rl 3.5 --wear-rr 2.5 "
      "--seed 7 --gnss-output latlon --out " +
      out);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("simulated    parking (ideal)"), std::string::npos) << run.out;
  const Log log = read_log(out);
  EXPECT_TRUE(log.gnss.origin.has_value());
  EXPECT_TRUE(log.truth && log.imu && log.heading);
  const std::string scenario = read_text_file(out + "/scenario.yaml");
  EXPECT_NE(scenario.find("wear_rl_mm: 3.5"), std::string::npos);
  EXPECT_NE(scenario.find("noise: 7"), std::string::npos);
  EXPECT_NE(read_text_file(out + "/truth.yaml").find("circumference_rl_m: 1.942132"),
            std::string::npos);
  // The effective scenario reproduces the same log.
  const std::string again = dir.file("again");
  ASSERT_EQ(run_cli("simulate --scenario " + out + "/scenario.yaml --out " + again).status, 0);
  EXPECT_TRUE(read_text_file(again + "/gnss.csv") == read_text_file(out + "/gnss.csv"));
}

TEST(SimulateCli, BadScenarioExitsWithStatusTwo) {
  const TempLogDir dir;
  dir.write("bad.yaml", "route:\n  segments:\n    - straight: -1\n");
  const auto run =
      run_cli("simulate --scenario " + dir.file("bad.yaml") + " --out " + dir.file("x"));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("bad.yaml:3: 'route.segments[0].straight'"), std::string::npos) << run.err;
  EXPECT_EQ(run_cli("simulate --scenario nowhere --out " + dir.file("y")).status, 2);
}

}  // namespace
}  // namespace odocal
