// A long log is prepared a block at a time: the blocks together are the log, each with its own
// standstills, wheel-rate bias, grade and gaps; a log shorter than two blocks is prepared whole.

#include "odocal/estimation/prepared_blocks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../support/hilly_urban.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/estimation/log_preparation.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Two laps of the urban block (stops at junctions and lights), angular-rate wheel sensors with
// zero-rate biases, a wheel gap.
Log urban_rate_sensor_log() {
  sim::Scenario scenario = load_scenario("urban");
  scenario.ideal = true;
  scenario.wheels.output = WheelUnit::kRadiansPerSecond;
  scenario.wheels.rate_bias_rl_radps = -0.33 * kDeg;
  scenario.wheels.rate_bias_rr_radps = 1.22 * kDeg;
  Log log = simulated_log(sim::simulate(scenario));
  // A 1.5 s gap in the wheels at 200 s.
  WheelStream& wheels = log.wheels;
  std::size_t k = 0;
  while (wheels.t_s[k] < 200.0) ++k;
  const std::size_t gap_end = k + 75;
  for (auto* column : {&wheels.t_s, &wheels.rev_rl, &wheels.rev_rr}) {
    column->erase(column->begin() + static_cast<std::ptrdiff_t>(k),
                  column->begin() + static_cast<std::ptrdiff_t>(gap_end));
  }
  return log;
}

CalibrationOptions in_blocks_of(double seconds) {
  CalibrationOptions options;
  options.prepare_block_s = seconds;
  return options;
}

TEST(PreparedBlocks, AGapLongerThanABlockAfterTheFirstSampleEndsTheSearchForTheStart) {
  // Found by fuzzing (log_pipeline): the search for the first motion asked again and again for
  // the window that starts at the first sample when the next one lay more than a block later.
  Log log = urban_rate_sensor_log();
  for (std::size_t k = 1; k < log.wheels.size(); ++k) log.wheels.t_s[k] += 5000.0;
  LogPreparation done;
  const std::optional<Log> prepared = prepare_log(log, in_blocks_of(600.0), done, false);
  EXPECT_FALSE(done.started_at_s.has_value());
  const Log& result = prepared ? *prepared : log;
  EXPECT_EQ(result.wheels.t_s.front(), log.wheels.t_s.front());
}

TEST(PreparedBlocks, TheBlocksTogetherAreTheLog) {
  const Log log = urban_rate_sensor_log();
  LogPreparation whole_done, blocks_done;
  const std::optional<Log> whole = prepare_log(log, CalibrationOptions{}, whole_done);
  const std::optional<Log> blocks = prepare_log(log, in_blocks_of(120.0), blocks_done);
  ASSERT_TRUE(whole && blocks);
  // Every sample once, in order, whatever the block length.
  ASSERT_EQ(blocks->wheels.t_s, whole->wheels.t_s);
  ASSERT_EQ(blocks->gnss.t_s, whole->gnss.t_s);
  ASSERT_EQ(blocks->imu->t_s, whole->imu->t_s);
  ASSERT_EQ(blocks->heading->t_s, whole->heading->t_s);
  // The gap is found once and breaks the chain in both.
  ASSERT_EQ(blocks_done.wheel_gaps.size(), 1u);
  ASSERT_EQ(whole_done.wheel_gaps.size(), 1u);
  EXPECT_DOUBLE_EQ(blocks_done.wheel_gaps[0].start_s, whole_done.wheel_gaps[0].start_s);
  EXPECT_EQ(blocks->wheels.chain_break, whole->wheels.chain_break);
  // Standstills split by a block boundary are one again.
  ASSERT_EQ(blocks_done.standstills.size(), whole_done.standstills.size());
  for (std::size_t i = 0; i < whole_done.standstills.size(); ++i) {
    EXPECT_NEAR(blocks_done.standstills[i].start_s, whole_done.standstills[i].start_s, 0.05);
    EXPECT_NEAR(blocks_done.standstills[i].end_s, whole_done.standstills[i].end_s, 0.05);
  }
  // Each block measures its own bias from its own stops: all the same sensor's.
  EXPECT_GT(blocks_done.wheel_rate_bias_per_block.size(), 1u);
  for (const auto& [from_s, bias] : blocks_done.wheel_rate_bias_per_block) {
    EXPECT_NEAR(360.0 * bias.rl_rev_per_s, -0.33, 0.02) << "block from " << from_s;
    EXPECT_NEAR(360.0 * bias.rr_rev_per_s, 1.22, 0.02) << "block from " << from_s;
  }
  ASSERT_TRUE(blocks_done.wheel_rate_bias.has_value());
  EXPECT_NEAR(360.0 * blocks_done.wheel_rate_bias->rr_rev_per_s, 1.22, 0.02);
  EXPECT_NE(blocks_done.describe().find("blocks' own"), std::string::npos)
      << blocks_done.describe();
  // The distance driven is the same to a fraction of a millimetre per kilometre.
  double whole_m = 0.0, blocks_m = 0.0;
  for (std::size_t k = 1; k < whole->wheels.size(); ++k) {
    whole_m += whole->wheels.rev_rl[k] + whole->wheels.rev_rr[k];
    blocks_m += blocks->wheels.rev_rl[k] + blocks->wheels.rev_rr[k];
  }
  EXPECT_NEAR(blocks_m / whole_m, 1.0, 1e-6);
}

TEST(PreparedBlocks, AShortLogIsOneBlockAndALongOneCalibratesAlike) {
  const Log log = urban_rate_sensor_log();
  InMemoryLogSource source(log);
  LogPreparation done;
  BlockPreparation blocks(source, CalibrationOptions{}, done);
  const auto block = blocks.next();
  ASSERT_TRUE(block.has_value());
  EXPECT_TRUE(block->first && block->last);
  EXPECT_FALSE(blocks.next().has_value());

  const BatchSummary whole = calibrate_batch(log);
  const BatchSummary in_blocks = calibrate_batch(log, {}, in_blocks_of(120.0));
  ASSERT_TRUE(whole.usable()) << whole.message;
  ASSERT_TRUE(in_blocks.usable()) << in_blocks.message;
  EXPECT_NEAR(in_blocks.estimate.circumference_rl_m, whole.estimate.circumference_rl_m,
              0.2 * whole.sigma_rl_m());
  EXPECT_NEAR(in_blocks.estimate.circumference_rr_m, whole.estimate.circumference_rr_m,
              0.2 * whole.sigma_rr_m());
}

TEST(PreparedBlocks, ABlockWithoutAltitudeHasNoGradeRatherThanALevelOne) {
  // The receiver gave no altitude for the first 300 s: the blocks there cannot fit a grade. Their
  // rows must not read "level" (a grade of 0 the verdict would test against), only "not known".
  Log log = simulated_log(sim::simulate(testing::hilly_urban()));
  for (std::size_t j = 0; j < log.gnss.size(); ++j) {
    if (log.gnss.t_s[j] < 300.0) log.gnss.altitude_m[j] = std::numeric_limits<double>::quiet_NaN();
  }
  LogPreparation done;
  const std::optional<Log> prepared = prepare_log(log, in_blocks_of(120.0), done);
  ASSERT_TRUE(prepared.has_value());
  const WheelStream& wheels = prepared->wheels;
  ASSERT_EQ(wheels.grade.size(), wheels.size());
  std::size_t unknown_early = 0, early = 0, graded_late = 0, late = 0;
  double steepest = 0.0;
  for (std::size_t k = 0; k < wheels.size(); ++k) {
    const bool known = std::isfinite(wheels.grade[k]);
    if (wheels.t_s[k] < 200.0) {
      ++early;
      unknown_early += known ? 0 : 1;
    } else if (wheels.t_s[k] > 400.0) {
      ++late;
      graded_late += known ? 1 : 0;
      if (known) steepest = std::max(steepest, std::abs(static_cast<double>(wheels.grade[k])));
    }
  }
  EXPECT_EQ(unknown_early, early);
  EXPECT_EQ(graded_late, late);
  EXPECT_GT(steepest, 0.03);
  // The driving state takes an unknown grade as level, as the unprojected increments are.
  for (const DrivingState& state : driving_states(*prepared, prepared->vehicle.nominal_params())) {
    ASSERT_TRUE(std::isfinite(state.specific_force_x_mps2));
  }
}

}  // namespace
}  // namespace odocal
