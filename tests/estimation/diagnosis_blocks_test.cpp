// The doctor reads a long log a block at a time: its comparison grid made block by block is the
// grid of the whole log, and its findings on the log streamed from the files are those of the
// log in memory.

#include <gtest/gtest.h>

#include <cmath>

#include "../support/run_cli.hpp"
#include "../support/temp_log_dir.hpp"
#include "estimation/diagnosis_facts.hpp"
#include "odocal/estimation/log_diagnosis.hpp"
#include "odocal/estimation/prepared_blocks.hpp"
#include "odocal/io/log_block_reader.hpp"
#include "odocal/io/log_reader.hpp"

namespace odocal {
namespace {

using testing::run_cli;
using testing::TempLogDir;

TEST(DiagnosisBlocks, TheGridMadeBlockByBlockIsTheWholeLogsGrid) {
  const TempLogDir dir;
  // 25 minutes: three blocks of the doctor's 10 minutes (the last one takes the rest).
  ASSERT_EQ(
      run_cli("simulate --scenario urban --laps 9 --gnss-altitude always --out " + dir.file("log"))
          .status,
      0);
  const Log log = read_log(dir.path() / "log", {{}, false});
  ASSERT_GT(log.wheels.t_s.back() - log.wheels.t_s.front(), 1200.0);
  const detail::DiagnosisSignals whole = detail::diagnosis_signals(log);
  InMemoryLogSource source(log);
  detail::DiagnosisSignals blocks;
  const detail::DiagnosisFacts facts = detail::diagnosis_facts(source, blocks);
  ASSERT_EQ(blocks.t_s, whole.t_s);
  // Equal, or both not available (NaN: no course when standing, no window at the ends).
  const auto same = [](double a, double b, double tolerance) {
    return (std::isnan(a) && std::isnan(b)) || std::abs(a - b) <= tolerance;
  };
  for (std::size_t k = 0; k < whole.size(); ++k) {
    // Cumulative wheel revolutions start at each block: a rounding apart.
    ASSERT_TRUE(same(blocks.speed_rl_mps[k], whole.speed_rl_mps[k], 1e-9)) << k;
    ASSERT_TRUE(same(blocks.wheel_yaw_rate_radps[k], whole.wheel_yaw_rate_radps[k], 1e-9)) << k;
    ASSERT_TRUE(same(blocks.gnss_speed_mps[k], whole.gnss_speed_mps[k], 0.0)) << k;
    ASSERT_TRUE(same(blocks.gnss_course_rate_radps[k], whole.gnss_course_rate_radps[k], 0.0)) << k;
    ASSERT_TRUE(same(blocks.gyro_radps[k], whole.gyro_radps[k], 0.0)) << k;
    ASSERT_TRUE(same(blocks.heading_rate_radps[k], whole.heading_rate_radps[k], 0.0)) << k;
  }
  EXPECT_EQ(facts.wheels.samples, log.wheels.size());
  EXPECT_EQ(facts.gnss.samples, log.gnss.size());
  EXPECT_DOUBLE_EQ(facts.gnss.last_s, log.gnss.t_s.back());
  EXPECT_TRUE(facts.standing);
  EXPECT_TRUE(facts.gnss_altitude);

  // Streamed from the files, the same findings (none: the log is clean).
  LogBlockReader reader(dir.path() / "log", {{}, false});
  const Diagnosis streamed = diagnose_log(reader);
  const Diagnosis in_memory = diagnose_log(log);
  EXPECT_TRUE(streamed.findings.empty()) << describe(streamed.findings.front());
  EXPECT_EQ(streamed.findings.size(), in_memory.findings.size());
  EXPECT_DOUBLE_EQ(streamed.compared_s, in_memory.compared_s);
}

}  // namespace
}  // namespace odocal
