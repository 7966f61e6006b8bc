// A lag between the GNSS and the wheels that the configuration does not estimate: the tyre terms
// read it as slip, and BatchOptions::detect_latency finds it (docs/batch-calibration.md, "A
// latency the log shows").

#include <gtest/gtest.h>

#include <cmath>

#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

// One lap of the realistic circuit, front-driven, a receiver with a Doppler column whose fixes
// are stamped `latency_s` after the position they report.
sim::SimulatedDrive lap_with_gnss_latency(double latency_s) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.route.laps = 1;
  scenario.dynamics.drivetrain = Drivetrain::kFront;
  scenario.vehicle.wear_rl_mm = 1.5;
  scenario.vehicle.wear_rr_mm = 1.0;
  scenario.gnss.speed_sigma_mps = 0.05;
  scenario.gnss.latency_s = latency_s;
  return sim::simulate(scenario);
}

TEST(LatencyDetection, ATyreFitThatReadsALagAsSlipIsFittedAgainWithTheLatency) {
  const sim::SimulatedDrive drive = lap_with_gnss_latency(0.09);
  const Log log = simulated_log(drive);
  const double truth_m = drive.true_params.circumference_rl_m;
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;

  // Not looked for, the physical terms take the lag for slip: ~10 mm off, beyond 2 of their
  // sigma, and their Doppler residual still follows a_x.
  options.detect_latency = false;
  const BatchSummary blind = calibrate_batch(log, options);
  ASSERT_EQ(blind.tyre_selection.chosen, "physical") << blind.full_report();
  EXPECT_GT(std::abs(blind.estimate.circumference_rl_m - truth_m), 2.0 * blind.sigma_rl_m())
      << blind.full_report();
  EXPECT_FALSE(blind.latency_detection.has_value());

  options.detect_latency = true;
  const BatchSummary found = calibrate_batch(log, options);
  ASSERT_TRUE(found.latency_detection.has_value()) << found.full_report();
  const BatchSummary::LatencyDetection& detection = *found.latency_detection;
  EXPECT_TRUE(detection.taken);
  EXPECT_EQ(detection.signature.quantity, "longitudinal acceleration");
  EXPECT_NEAR(detection.latency_s, 0.09, 3.0 * detection.sigma_s + 0.005);
  EXPECT_DOUBLE_EQ(detection.circumference_without_m[0], blind.estimate.circumference_rl_m);
  EXPECT_LT(std::abs(found.estimate.circumference_rl_m - truth_m), 3.0 * found.sigma_rl_m())
      << found.full_report();
  EXPECT_LT(std::abs(found.estimate.circumference_rl_m - truth_m), 0.002);
  EXPECT_NE(found.full_report().find("latency      the fit without it left the"), std::string::npos)
      << found.full_report();
  // As if it had been asked for.
  options.estimate_latency = true;
  const BatchSummary asked = calibrate_batch(log, options);
  EXPECT_DOUBLE_EQ(asked.estimate.circumference_rl_m, found.estimate.circumference_rl_m);
  EXPECT_FALSE(asked.latency_detection.has_value());
}

TEST(LatencyDetection, ALogWithoutALagIsNotFittedAgain) {
  const Log log = simulated_log(lap_with_gnss_latency(0.0));
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  const BatchSummary summary = calibrate_batch(log, options);
  EXPECT_EQ(summary.tyre_selection.chosen, "physical") << summary.full_report();
  EXPECT_FALSE(summary.latency_detection.has_value()) << summary.full_report();
}

}  // namespace
}  // namespace odocal
