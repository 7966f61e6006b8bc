// The batch's result does not depend on how many threads pre-integrate and fold the log: the
// same to the last bit on one thread and on several (parallel_parts.hpp), through every path
// that the parts take (tyre terms and the driving states they re-measure, the Doppler residual,
// heading samples, the robust loss's weights, the noise adaptation's re-solves).

#include <gtest/gtest.h>

#include "../support/test_scenarios.hpp"
#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

BatchSummary calibrate_on(const Log& log, int threads) {
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kPhysical;
  options.threads = threads;
  options.keyframe_interval_s = 0.25;  // a lap of 216 s in parts of at least 256 intervals
  return calibrate_batch(log, options, CalibrationOptions{});
}

TEST(BatchThreads, TheResultIsTheSameToTheLastBitOnAnyNumberOfThreads) {
  // One realistic lap (rear-driven, its tyres slipping) with a Doppler column, fitted with the
  // physical terms through several re-linearisations, and their regression witness.
  sim::Scenario scenario = testing::realistic_lap_on_track(0.0, 3);
  scenario.gnss.speed_sigma_mps = 0.05;
  const Log log = simulated_log(sim::simulate(scenario));
  const BatchSummary one = calibrate_on(log, 1);
  ASSERT_GE(one.keyframes, 3 * 256u) << "too short to be split into three parts";
  for (const int threads : {2, 3}) {
    const BatchSummary several = calibrate_on(log, threads);
    EXPECT_EQ(several.estimate.circumference_rl_m, one.estimate.circumference_rl_m);
    EXPECT_EQ(several.estimate.circumference_rr_m, one.estimate.circumference_rr_m);
    EXPECT_EQ(several.covariance, one.covariance);
    EXPECT_EQ(several.solves, one.solves);
    EXPECT_EQ(several.after.mean_position_m, one.after.mean_position_m);
    // Everything it reports, word for word (the configuration aside, which names the threads).
    EXPECT_EQ(several.full_report(), one.full_report());
  }
}

}  // namespace
}  // namespace odocal
