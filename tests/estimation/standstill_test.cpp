// Standing still: found by wheels, GNSS and gyro together; angular-rate wheel sensors' zero-rate
// biases estimated there and removed, so that they add neither distance nor heading; the log is
// used from its first motion on.

#include "odocal/estimation/standstill.hpp"

#include <gtest/gtest.h>

#include <numbers>

#include "../support/unjudged_options.hpp"
#include "experiments/worn_circuit.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/estimation/log_window.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Log rate_sensor_lap(double bias_rl_deg_s, double bias_rr_deg_s, double dwell_s) {
  sim::Scenario scenario = experiments::worn_ideal_circuit(1, 1);
  scenario.driver.start_dwell_s = dwell_s;  // standing at the start and at the end
  scenario.wheels.output = WheelUnit::kRadiansPerSecond;
  scenario.wheels.rate_bias_rl_radps = bias_rl_deg_s * kDeg;
  scenario.wheels.rate_bias_rr_radps = bias_rr_deg_s * kDeg;
  return simulated_log(sim::simulate(scenario));
}

TEST(Standstill, FoundAtTheStartAndTheEnd) {
  const Log log = rate_sensor_lap(0.0, 0.0, 30.0);
  const std::vector<Standstill> standing = find_standstills(log, log.vehicle.nominal_params());
  ASSERT_EQ(standing.size(), 2u);
  EXPECT_NEAR(standing[0].start_s, log.wheels.t_s.front(), 0.1);
  EXPECT_NEAR(standing[0].end_s - standing[0].start_s, 30.0, 1.0);
  EXPECT_NEAR(standing[1].end_s, log.wheels.t_s.back(), 0.1);
  const auto moving = first_motion_s(log.wheels, log.vehicle.nominal_params(), 0.5);
  ASSERT_TRUE(moving.has_value());
  EXPECT_NEAR(*moving, standing[0].end_s, 2.0);
}

TEST(Standstill, WheelRateBiasesAreRemovedAndChangeNothingElse) {
  const Log clean = rate_sensor_lap(0.0, 0.0, 30.0);
  const Log biased = rate_sensor_lap(-0.33, 1.22, 30.0);
  const CalibrationOptions unjudged = testing::unjudged_options();
  const IterativeSummary reference = calibrate_iterative(clean, {}, unjudged);
  const IterativeSummary result = calibrate_iterative(biased, {}, unjudged);
  ASSERT_TRUE(result.preparation.wheel_rate_bias.has_value());
  EXPECT_NEAR(360.0 * result.preparation.wheel_rate_bias->rl_rev_per_s, -0.33, 0.02);
  EXPECT_NEAR(360.0 * result.preparation.wheel_rate_bias->rr_rev_per_s, 1.22, 0.02);
  EXPECT_TRUE(result.usable()) << result.message;
  EXPECT_LT(std::abs(result.estimate.circumference_rl_m - reference.estimate.circumference_rl_m),
            reference.sigma_rl_m());
  EXPECT_LT(std::abs(result.estimate.circumference_rr_m - reference.estimate.circumference_rr_m),
            reference.sigma_rr_m());
  EXPECT_NE(result.full_report().find("wheel rate bias removed: RL -0.3"), std::string::npos)
      << result.full_report();
  // Left in, the biases move the batch's left/right difference by many of its sigma.
  CalibrationOptions keep_bias;
  keep_bias.remove_wheel_rate_bias = false;
  const BatchSummary batch_reference = calibrate_batch(clean);
  const BatchSummary batch_removed = calibrate_batch(biased);
  const BatchSummary batch_kept = calibrate_batch(biased, {}, keep_bias);
  const auto difference = [](const CalibrationSummary& s) {
    return s.estimate.circumference_rr_m - s.estimate.circumference_rl_m;
  };
  EXPECT_LT(std::abs(difference(batch_removed) - difference(batch_reference)),
            2.0 * batch_reference.sigma_rr_m());
  EXPECT_GT(std::abs(difference(batch_kept) - difference(batch_reference)),
            3.0 * batch_reference.sigma_rr_m());
}

TEST(Standstill, TheLogIsUsedFromItsFirstMotion) {
  const Log log = rate_sensor_lap(0.0, 0.0, 60.0);
  const BatchSummary result = calibrate_batch(log);
  ASSERT_TRUE(result.preparation.started_at_s.has_value());
  EXPECT_NEAR(*result.preparation.started_at_s, log.wheels.t_s.front() + 59.0, 1.5);
  EXPECT_TRUE(result.usable()) << result.message;
}

TEST(LogWindow, CropsEveryStreamAndStartsTheWheelChain) {
  const Log log = rate_sensor_lap(0.0, 0.0, 1.0);
  const Log window = crop_log(log, 100.0, 150.0);
  EXPECT_GE(window.wheels.t_s.front(), 100.0);
  EXPECT_LE(window.wheels.t_s.back(), 150.0);
  EXPECT_EQ(window.wheels.rev_rl.front(), 0.0);
  EXPECT_GE(window.gnss.t_s.front(), 100.0);
  EXPECT_LE(window.imu->t_s.back(), 150.0);
  EXPECT_EQ(window.wheels.t_s.size(), window.wheels.rev_rr.size());
  EXPECT_THROW(crop_log(log, 1e6, 2e6), InsufficientDataError);
}

}  // namespace
}  // namespace odocal
