// Distance and turning while moving, against closed-form motion: standing still and sensor noise
// add neither.

#include "odocal/estimation/motion_coverage.hpp"

#include <gtest/gtest.h>

#include <random>

#include "odocal/estimation/calibration.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

const OdometryParams kParams{2.0, 2.0, 1.6};

// Appends `seconds` at 50 Hz of speed v and yaw rate w (exact wheel revolutions), plus noise.
void drive(Log& log, double seconds, double v, double w, double noise_rev = 0.0) {
  std::mt19937 rng(static_cast<unsigned>(log.wheels.size()));
  std::normal_distribution<double> unit(0.0, 1.0);  // times noise_rev: a sigma of 0 is allowed
  const auto normal = [&](std::mt19937& g) { return noise_rev * unit(g); };
  const double dt = 0.02;
  for (int i = 0; i < static_cast<int>(seconds / dt + 0.5); ++i) {
    const double t = log.wheels.t_s.empty() ? 0.0 : log.wheels.t_s.back() + dt;
    log.wheels.t_s.push_back(t);
    const double left = (v - 0.5 * w * kParams.track_width_m) * dt;
    const double right = (v + 0.5 * w * kParams.track_width_m) * dt;
    log.wheels.rev_rl.push_back(log.wheels.t_s.size() == 1 ? 0.0 : left / 2.0 + normal(rng));
    log.wheels.rev_rr.push_back(log.wheels.t_s.size() == 1 ? 0.0 : right / 2.0 + normal(rng));
  }
}

TEST(MotionCoverage, CountsDistanceAndTurnsWhileMovingOnly) {
  Log log;
  drive(log, 10.0, 0.0, 0.0, 1e-4);  // standing, with encoder jitter
  drive(log, 10.0, 10.0, 0.1);       // 100 m, 1 rad to the left
  drive(log, 10.0, 10.0, 0.0);       // 100 m straight
  drive(log, 5.0, 10.0, -0.1);       // 50 m, 0.5 rad to the right
  drive(log, 10.0, 0.0, 0.0, 1e-4);  // standing again
  const MotionCoverage c = motion_coverage(log, kParams, 0.0, 1e9);
  EXPECT_NEAR(c.distance_m, 250.0, 0.5);
  EXPECT_NEAR(c.moving_s, 25.0, 0.1);
  EXPECT_NEAR(c.left_turning_rad, 1.0, 0.03);
  EXPECT_NEAR(c.right_turning_rad, 0.5, 0.03);
  EXPECT_EQ(c.turning_source, "wheels");
}

TEST(MotionCoverage, MeanSquareSpeedIsWeightedByDistance) {
  // 1000 m at 10 m/s and 1000 m at 20 m/s: (1000 * 100 + 1000 * 400) / 2000 = 250 (m/s)^2,
  // where a mean over time would give 200; standing and the encoders' jitter add nothing.
  Log log;
  drive(log, 10.0, 0.0, 0.0, 1e-4);
  drive(log, 100.0, 10.0, 0.05, 1e-3);
  drive(log, 50.0, 20.0, 0.0, 1e-3);
  drive(log, 10.0, 0.0, 0.0, 1e-4);
  const MotionCoverage c = motion_coverage(log, kParams, 0.0, 1e9);
  EXPECT_NEAR(c.mean_square_speed_m2ps2(), 250.0, 2.0);
  EXPECT_EQ(MotionCoverage{}.mean_square_speed_m2ps2(), 0.0);
}

TEST(MotionCoverage, AGyroWithNoiseAndBiasSeesNoTurningOnAStraight) {
  Log log;
  drive(log, 120.0, 15.0, 0.0);
  ImuStream imu;
  std::mt19937 rng(1);
  std::normal_distribution<double> noise(0.0, 0.02);  // rad/s, the paper's gyro
  for (double t = 0.0; t <= 120.0; t += 0.02) {
    imu.t_s.push_back(t);
    imu.ax_mps2.push_back(0.0);
    imu.ay_mps2.push_back(0.0);
    imu.wz_radps.push_back(0.01 + noise(rng));  // and a 0.6 deg/s bias
  }
  log.imu = imu;
  const MotionCoverage c = motion_coverage(log, kParams, 0.0, 1e9);
  EXPECT_EQ(c.turning_source, "gyro");
  EXPECT_EQ(c.turning_rad(), 0.0);
  EXPECT_NEAR(c.distance_m, 1800.0, 1.0);
}

TEST(MotionCoverage, AStraightDriveWithATightGnssSigmaGetsACommonScaleOnly) {
  sim::Scenario scenario =
      parse_scenario("route:\n  segments:\n    - straight: 3000\n", "straight.yaml");
  scenario.ideal = true;
  const Log log = simulated_log(sim::simulate(scenario));
  CalibrationOptions common;
  common.reference.gnss_sigma_m = 0.05;  // the kind of sigma that once split left from right
  const IterativeSummary result = calibrate_iterative(log, {}, common);
  EXPECT_FALSE(result.difference_identifiable);
  EXPECT_NE(result.identifiability.find("0 deg of turning while moving"), std::string::npos)
      << result.identifiability;
  EXPECT_DOUBLE_EQ(result.estimate.circumference_rl_m / result.nominal.circumference_rl_m,
                   result.estimate.circumference_rr_m / result.nominal.circumference_rr_m);
}

}  // namespace
}  // namespace odocal
