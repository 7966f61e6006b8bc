// A GNSS antenna off the rear axle's centre and a heading.csv read off by a mount's yaw, which the
// configuration does not state: BatchOptions::detect_mounting finds them in the fit's residuals
// and fits the log again with them estimated (docs/batch-calibration.md, "The mounting the log
// shows").

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

// The built-in urban drive (5 minutes of mostly left-hand loops) with a Doppler column.
sim::SimulatedDrive urban_drive(double heading_bias_rad = 0.0) {
  sim::Scenario scenario = load_scenario("urban");
  scenario.gnss.speed_sigma_mps = 0.05;
  scenario.heading.bias_rad = heading_bias_rad;
  return sim::simulate(scenario);
}

// The fixes as an antenna `ahead_m` ahead of and `left_m` left of the rear axle's centre reports
// them: its position turned with the vehicle, its Doppler speed that of the point turning about the
// axle's centre.
void move_antenna(sim::SimulatedDrive& drive, double ahead_m, double left_m) {
  const PoseStream& truth = drive.truth;
  std::size_t k = 0;
  for (std::size_t j = 0; j < drive.gnss_t_s.size(); ++j) {
    while (k + 2 < truth.size() && truth.t_s[k + 1] <= drive.gnss_t_s[j]) ++k;
    const double yaw = truth.pose[k].z();
    const double yaw_rate =
        (truth.pose[k + 1].z() - truth.pose[k].z()) / (truth.t_s[k + 1] - truth.t_s[k]);
    drive.gnss_a[j] += std::cos(yaw) * ahead_m - std::sin(yaw) * left_m;
    drive.gnss_b[j] += std::sin(yaw) * ahead_m + std::cos(yaw) * left_m;
    if (!drive.gnss_speed_mps.empty()) {
      drive.gnss_speed_mps[j] =
          std::hypot(drive.gnss_speed_mps[j] - yaw_rate * left_m, yaw_rate * ahead_m);
    }
  }
}

BatchOptions options_that_report() {
  BatchOptions options;
  options.max_sigma_circumference_m = 0.005;
  return options;
}

double error_rl(const BatchSummary& s, const sim::SimulatedDrive& drive) {
  return s.estimate.circumference_rl_m - drive.true_params.circumference_rl_m;
}

TEST(MountingDetection, AnAntennaLeftOfTheCentreIsFoundAndItsFitStands) {
  sim::SimulatedDrive drive = urban_drive();
  move_antenna(drive, 0.0, 0.5);
  const Log log = simulated_log(drive);
  BatchOptions options = options_that_report();

  // Not looked for: the Doppler speed's residual follows every turn, its noise is widened six
  // times, and the circumferences' sigma with it.
  options.detect_mounting = false;
  const BatchSummary blind = calibrate_batch(log, options);
  EXPECT_GT(blind.doppler_sigma_scale, 3.0) << blind.full_report();
  EXPECT_FALSE(blind.mounting_detection.has_value());

  options.detect_mounting = true;
  const BatchSummary found = calibrate_batch(log, options);
  ASSERT_TRUE(found.mounting_detection.has_value()) << found.full_report();
  const BatchSummary::MountingDetection& detection = *found.mounting_detection;
  EXPECT_TRUE(detection.lever_arm);
  EXPECT_FALSE(detection.heading_bias);
  EXPECT_TRUE(detection.taken);
  EXPECT_NEAR(detection.signature.doppler_left_m, 0.5, 0.05);
  EXPECT_NEAR(detection.lever_arm_m[1], 0.5, 3.0 * detection.lever_arm_sigma_m[1] + 0.01);
  EXPECT_DOUBLE_EQ(detection.circumference_without_m[0], blind.estimate.circumference_rl_m);
  EXPECT_EQ(found.termination, Termination::kConverged) << found.full_report();
  EXPECT_LT(found.doppler_sigma_scale, 1.5) << found.full_report();
  EXPECT_LT(std::abs(error_rl(found, drive)), 3.0 * found.sigma_rl_m()) << found.full_report();
  EXPECT_LT(found.sigma_rl_m(), 0.5 * blind.sigma_rl_m());
  EXPECT_NE(found.full_report().find("mounting     the fit without them left the GNSS fixes"),
            std::string::npos)
      << found.full_report();

  // Stated, it is held there and nothing is looked for.
  options.lever_arm_y_m = 0.5;
  const BatchSummary stated = calibrate_batch(log, options);
  EXPECT_FALSE(stated.mounting_detection.has_value()) << stated.full_report();
  EXPECT_LT(std::abs(error_rl(stated, drive)), 3.0 * stated.sigma_rl_m()) << stated.full_report();
  EXPECT_NEAR(stated.estimate.circumference_rl_m, found.estimate.circumference_rl_m,
              found.sigma_rl_m());
}

// Ahead of the axle, the antenna's Doppler speed is the hypotenuse of the axle's and the yaw rate
// times the lever: a yaw rate of one wheel sample, quantised by the encoders, put the stated
// antenna's fit 1.6 sigma low with its Doppler noise 1.4 times the configured.
TEST(MountingDetection, AnAntennaAheadOfTheAxleIsFoundAndAsStatedFitsAsOnTheAxle) {
  sim::SimulatedDrive drive = urban_drive();
  move_antenna(drive, 1.5, 0.3);
  const Log log = simulated_log(drive);
  BatchOptions options = options_that_report();
  const BatchSummary found = calibrate_batch(log, options);
  ASSERT_TRUE(found.mounting_detection.has_value()) << found.full_report();
  const BatchSummary::MountingDetection& detection = *found.mounting_detection;
  EXPECT_TRUE(detection.taken);
  EXPECT_NEAR(detection.lever_arm_m[0], 1.5, 3.0 * detection.lever_arm_sigma_m[0] + 0.01);
  EXPECT_NEAR(detection.lever_arm_m[1], 0.3, 3.0 * detection.lever_arm_sigma_m[1] + 0.01);
  EXPECT_LT(std::abs(error_rl(found, drive)), 3.0 * found.sigma_rl_m()) << found.full_report();

  options.lever_arm_x_m = 1.5;
  options.lever_arm_y_m = 0.3;
  const BatchSummary stated = calibrate_batch(log, options);
  EXPECT_EQ(stated.termination, Termination::kConverged) << stated.full_report();
  EXPECT_LT(stated.doppler_sigma_scale, 1.2) << stated.full_report();
  EXPECT_LT(std::abs(error_rl(stated, drive)), 2.0 * stated.sigma_rl_m()) << stated.full_report();
}

TEST(MountingDetection, AHeadingReadOffByAMountsYawIsFoundAndEstimated) {
  const sim::SimulatedDrive drive = urban_drive(0.05);
  const Log log = simulated_log(drive);
  BatchOptions options = options_that_report();
  options.detect_mounting = false;
  const BatchSummary blind = calibrate_batch(log, options);
  EXPECT_FALSE(blind.mounting_detection.has_value());

  options.detect_mounting = true;
  const BatchSummary found = calibrate_batch(log, options);
  ASSERT_TRUE(found.mounting_detection.has_value()) << found.full_report();
  const BatchSummary::MountingDetection& detection = *found.mounting_detection;
  EXPECT_TRUE(detection.heading_bias);
  EXPECT_FALSE(detection.lever_arm);
  EXPECT_GT(detection.signature.heading_mean_rad,
            10.0 * detection.signature.heading_standard_error_rad);
  EXPECT_TRUE(detection.taken);
  EXPECT_NEAR(detection.heading_bias_rad, 0.05, 3.0 * detection.heading_bias_sigma_rad);
  EXPECT_EQ(found.termination, Termination::kConverged) << found.full_report();
  EXPECT_LT(std::abs(error_rl(found, drive)), 3.0 * found.sigma_rl_m()) << found.full_report();
}

TEST(MountingDetection, AMountingAsStatedIsNotFittedAgain) {
  const Log log = simulated_log(urban_drive());
  const BatchSummary summary = calibrate_batch(log, options_that_report());
  EXPECT_FALSE(summary.mounting_detection.has_value()) << summary.full_report();
  const MountingResiduals& m = summary.mounting_residuals;
  ASSERT_TRUE(m.gnss && m.heading && m.doppler);
  for (std::size_t a = 0; a < 2; ++a)
    EXPECT_LT(std::abs(m.gnss_mean_m[a]), 3.0 * m.gnss_standard_error_m[a]);
  EXPECT_LT(std::abs(m.doppler_left_m), 3.0 * m.doppler_left_standard_error_m);
  EXPECT_LT(std::abs(m.heading_mean_rad), 3.0 * m.heading_standard_error_rad);
}

}  // namespace
}  // namespace odocal
