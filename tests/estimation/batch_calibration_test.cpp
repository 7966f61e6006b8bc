// The batch maximum-likelihood calibration: residual derivatives against numerical ones, wear
// recovered on simulated drives within the reported uncertainty, optional unknowns, robustness
// to GNSS outliers, and the observability verdicts.

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "estimation/batch_residuals.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

// Checks a cost function's Jacobians against central differences at a given point.
void expect_correct_jacobians(const ceres::CostFunction& cost,
                              std::vector<std::vector<double>> values) {
  std::vector<const double*> parameters;
  for (const auto& block : values) parameters.push_back(block.data());
  ceres::NumericDiffOptions numeric;
  const std::vector<const ceres::Manifold*>* no_manifolds = nullptr;
  const ceres::GradientChecker checker(&cost, no_manifolds, numeric);
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(parameters.data(), 1e-7, &results)) << results.error_log;
}

batch::RelativeMotion some_motion() {
  batch::RelativeMotion motion;
  motion.delta << 12.0, 1.5, 0.3;
  motion.J_delta_params << 3.1, 3.0, -0.2, 0.4, -0.5, 0.9, -0.8, 0.8, -0.1;
  motion.J_delta_first_increment << 1.0, 0.9, -0.3, 0.35, -1.2, 1.25;
  motion.params_lin << 1.95, 1.96, 1.6;
  return motion;
}

TEST(BatchResiduals, JacobiansMatchNumericalOnes) {
  const std::vector<double> pose_a{10.0, -4.0, 2.9}, pose_b{21.0, -1.0, 3.3};
  const std::vector<double> params{1.951, 1.958, 1.62};
  Eigen::Matrix3d sqrt_information;
  sqrt_information << 3.0, 0.2, 0.1, 0.0, 2.5, -0.3, 0.0, 0.0, 40.0;
  expect_correct_jacobians(
      ceres::AutoDiffCostFunction<batch::OdometryResidual, 3, 3, 3, 3, 2, 2>(
          new batch::OdometryResidual{some_motion(), some_motion().J_delta_first_increment,
                                      sqrt_information}),
      {pose_a, pose_b, params, {0.002, -0.001}, {-0.003, 0.001}});
  expect_correct_jacobians(
      ceres::AutoDiffCostFunction<batch::GnssResidual, 2, 3, 3, 2, 1, 2, 2>(
          new batch::GnssResidual{some_motion(), {20.0, 3.0}, {22.0, 5.0}, 2.5}),
      {pose_a, params, {0.4, -0.2}, {0.05}, {0.7, -1.1}, {0.002, -0.001}});
  expect_correct_jacobians(ceres::AutoDiffCostFunction<batch::HeadingResidual, 1, 3, 3, 1, 2>(
                               new batch::HeadingResidual{some_motion(), -3.0, 0.15}),
                           {pose_a, params, {0.02}, {0.002, -0.001}});
  expect_correct_jacobians(ceres::AutoDiffCostFunction<batch::GyroResidual, 1, 3, 3, 1>(
                               new batch::GyroResidual{0.35, 1.0, 0.003}),
                           {pose_a, pose_b, {0.001}});
  expect_correct_jacobians(ceres::AutoDiffCostFunction<batch::GaussMarkovResidual, 2, 2, 2>(
                               new batch::GaussMarkovResidual{0.98, 0.4}),
                           {{1.0, -2.0}, {0.9, -1.7}});
}

TEST(BatchResiduals, VanishAtTheirClosedFormSolutions) {
  // Keyframe a at (10, -4) heading 90 deg; the motion moves 12 m forward, 1.5 m left, turns 0.3.
  const double pose_a[3] = {10.0, -4.0, M_PI / 2};
  const double pose_b[3] = {10.0 - 1.5, -4.0 + 12.0, M_PI / 2 + 0.3};
  const double params[3] = {1.95, 1.96, 1.6};  // = params_lin: no first-order change
  const double no_count_error[2] = {0.0, 0.0};
  double residual[3];
  batch::OdometryResidual{some_motion(), Eigen::Matrix<double, 3, 2>::Zero(),
                          Eigen::Matrix3d::Identity()}(pose_a, pose_b, params, no_count_error,
                                                       no_count_error, residual);
  EXPECT_NEAR(Eigen::Vector3d(residual[0], residual[1], residual[2]).norm(), 0.0, 1e-12);
  // GNSS antenna 1 m ahead of the reference point, 0.1 s latency at 10 m/s forward (keyframe
  // frame x = world y here), 0.5 m east bias.
  const double lever[2] = {1.0, 0.0}, latency[1] = {0.1}, bias[2] = {0.5, 0.0};
  const double yaw = M_PI / 2 + 0.3;
  const Eigen::Vector2d expected(10.0 - 1.5 + std::cos(yaw) + 0.5,
                                 -4.0 + 12.0 + std::sin(yaw) - 10.0 * 0.1);
  batch::GnssResidual{some_motion(), {10.0, 0.0}, expected, 1.0}(pose_a, params, lever, latency,
                                                                 bias, no_count_error, residual);
  EXPECT_NEAR(std::hypot(residual[0], residual[1]), 0.0, 1e-12);
}

sim::Scenario ideal_lap() {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  scenario.route.laps = 1;
  scenario.vehicle.wear_rl_mm = 1.5;
  scenario.vehicle.wear_rr_mm = 1.0;
  return scenario;
}

CalibrationOptions batch_options() {
  CalibrationOptions options;
  options.method = CalibrationMethod::kBatch;
  return options;
}

void expect_within_3_sigma(const CalibrationResult& result, const OdometryParams& truth) {
  const double error_rl = result.estimate.circumference_rl_m - truth.circumference_rl_m;
  const double error_rr = result.estimate.circumference_rr_m - truth.circumference_rr_m;
  EXPECT_LT(std::abs(error_rl), 3.0 * std::sqrt(result.covariance(0, 0)));
  EXPECT_LT(std::abs(error_rr), 3.0 * std::sqrt(result.covariance(1, 1)));
  EXPECT_LT(std::abs(error_rl), 5e-4);
  EXPECT_LT(std::abs(error_rr), 5e-4);
}

TEST(BatchCalibration, RecoversTheWearWithinItsReportedUncertainty) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    sim::Scenario scenario = ideal_lap();
    scenario.seeds.noise = seed;
    const sim::SimulatedDrive drive = sim::simulate(scenario);
    const CalibrationResult result = calibrate(simulated_log(drive), batch_options());
    SCOPED_TRACE(result.termination);
    EXPECT_NE(result.termination.find("CONVERGENCE"), std::string::npos);
    expect_within_3_sigma(result, drive.true_params);
    EXPECT_EQ(result.identifiability, "every requested parameter identified");
    EXPECT_LT(result.after.mean_position_m, result.before.mean_position_m);
  }
}

TEST(BatchCalibration, EstimatesTrackWidthGyroBiasAndLatencyWhenAsked) {
  sim::Scenario scenario = ideal_lap();
  scenario.imu.gyro_bias_radps = 0.01;
  scenario.gnss.latency_s = 0.1;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  Log log = simulated_log(drive);
  log.vehicle.track_width_m = 1.55;  // vehicle.yaml is 5 cm off
  CalibrationOptions options = batch_options();
  options.batch.estimate_track_width = true;
  options.batch.estimate_gyro_bias = true;
  options.batch.estimate_latency = true;
  const CalibrationResult result = calibrate(log, options);
  const auto find = [&](const std::string& name) {
    for (const EstimatedParameter& p : result.parameters)
      if (p.name == name) return p;
    ADD_FAILURE() << name;
    return EstimatedParameter{};
  };
  const EstimatedParameter track = find("track_width_m");
  EXPECT_TRUE(track.identified) << track.verdict;
  EXPECT_LT(std::abs(track.value - 1.6), 3.0 * track.sigma);
  const EstimatedParameter gyro = find("gyro_bias_radps");
  EXPECT_LT(std::abs(gyro.value - 0.01), 3.0 * gyro.sigma);
  const EstimatedParameter latency = find("latency_s");
  EXPECT_LT(std::abs(latency.value - 0.1), 3.0 * latency.sigma + 1e-3);
  EXPECT_FALSE(find("heading_bias_rad").estimated);
  expect_within_3_sigma(result, drive.true_params);
}

TEST(BatchCalibration, RobustLossKeepsGnssOutliersOut) {
  // Multipath in one place: 2 % of the fixes, in one stretch, 30 m off to the east. The squared
  // loss bends the trajectory towards them; the robust losses mostly ignore them.
  const sim::SimulatedDrive drive = sim::simulate(ideal_lap());
  const Log clean = simulated_log(drive);
  Log log = clean;
  const std::size_t first = log.gnss.size() / 3, count = log.gnss.size() / 50;
  for (std::size_t j = first; j < first + count; ++j) log.gnss.x_m[j] += 30.0;
  const CalibrationResult reference = calibrate(clean, batch_options());
  const auto moved = [&](const CalibrationOptions& options) {
    const CalibrationResult r = calibrate(log, options);
    return std::hypot(r.estimate.circumference_rl_m - reference.estimate.circumference_rl_m,
                      r.estimate.circumference_rr_m - reference.estimate.circumference_rr_m);
  };
  const double cauchy = moved(batch_options());
  CalibrationOptions options = batch_options();
  options.batch.gnss_loss = RobustLoss::kNone;
  const double squared = moved(options);
  options.batch.gnss_loss = RobustLoss::kHuber;
  const double huber = moved(options);
  EXPECT_LT(cauchy, 0.75 * std::sqrt(reference.covariance(0, 0)));
  EXPECT_GT(squared, 3.0 * cauchy);
  EXPECT_LT(huber, squared);
}

TEST(BatchCalibration, SaysWhatAStraightDriveCannotIdentify) {
  sim::Scenario scenario =
      parse_scenario("route:\n  segments:\n    - straight: 3000\n", "straight.yaml");
  scenario.ideal = true;
  Log log = simulated_log(sim::simulate(scenario));
  log.heading.reset();
  CalibrationOptions options = batch_options();
  options.batch.estimate_track_width = true;
  options.batch.estimate_heading_bias = true;
  options.min_heading_range_for_difference_rad = 0.0;
  const CalibrationResult result = calibrate(log, options);
  bool track_said = false, heading_said = false;
  for (const EstimatedParameter& p : result.parameters) {
    if (p.name == "track_width_m") {
      EXPECT_FALSE(p.identified);
      track_said = p.verdict.find("needs more turns") != std::string::npos;
    }
    if (p.name == "heading_bias_rad") {
      EXPECT_FALSE(p.identified);
      heading_said = p.verdict.find("no heading reference") != std::string::npos;
    }
  }
  EXPECT_TRUE(track_said) << result.identifiability;
  EXPECT_TRUE(heading_said) << result.identifiability;
  EXPECT_NE(result.identifiability.find("not identified"), std::string::npos);
}

}  // namespace
}  // namespace odocal
