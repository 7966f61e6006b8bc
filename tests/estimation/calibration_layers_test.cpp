// The layers of the calibration checked against independent truth: the EKF against a
// hand-computed two-step case, the least squares against exact synthetic data, the reference
// filter against simulated truth and its own covariance.

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>
#include <random>
#include <span>

#include "odocal/estimation/circumference_ls.hpp"
#include "odocal/estimation/odometry_ekf.hpp"
#include "odocal/estimation/reference_filter.hpp"
#include "odocal/estimation/trajectory_errors.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

TEST(OdometryEkf, MatchesTheHandComputedTwoStepCase) {
  // Straight east, 0.5 rev per step of 2 m wheels: the model moves 1 m per step. P = M = I makes
  // every gain closed-form: step 1: S- = M + P = 2I, G = 2/3 I; step 2: S- = 2/3 + 1 = 5/3,
  // G = (5/3) / (8/3) = 5/8.
  WheelStream wheels;
  wheels.t_s = {0.0, 1.0, 2.0};
  wheels.rev_rl = {0.0, 0.5, 0.5};
  wheels.rev_rr = {0.0, 0.5, 0.5};
  ReferenceTrajectory reference;
  reference.poses = {Pose2(0, 0, 0), Pose2(1.3, 0.3, 0.03), Pose2(2.0, 0.0, 0.0)};
  std::vector<Pose2> x_hat;
  run_odometry_ekf(wheels, reference, {2.0, 2.0, 1.6},
                   {Eigen::Vector3d::Ones(), Eigen::Vector3d::Ones()}, x_hat);
  ASSERT_EQ(x_hat.size(), 3u);
  // Step 1: prediction (1, 0, 0); update with gain 2/3 toward (1.3, 0.3, 0.03). Heading and y
  // couple through F, so compute the full matrices by hand in the order of eqs. 5-8.
  Eigen::Matrix3d F1;  // at yaw 0 with ds = 1: d x / d yaw = 0, d y / d yaw = 1
  F1 << 1, 0, 0, 0, 1, 1, 0, 0, 1;
  Eigen::Matrix3d sigma =
      F1 * Eigen::Matrix3d::Identity() * F1.transpose() + Eigen::Matrix3d::Identity();
  Eigen::Matrix3d G = sigma * (sigma + Eigen::Matrix3d::Identity()).inverse();
  Eigen::Vector3d x1 =
      Eigen::Vector3d(1, 0, 0) + G * (Eigen::Vector3d(1.3, 0.3, 0.03) - Eigen::Vector3d(1, 0, 0));
  EXPECT_LT((x_hat[1] - x1).norm(), 1e-12);
  sigma = (Eigen::Matrix3d::Identity() - G) * sigma;
  Eigen::Matrix3d F2;
  const double yaw = x1.z();
  F2 << 1, 0, -std::sin(yaw), 0, 1, std::cos(yaw), 0, 0, 1;
  const Eigen::Vector3d predicted(x1.x() + std::cos(yaw), x1.y() + std::sin(yaw), yaw);
  sigma = F2 * sigma * F2.transpose() + Eigen::Matrix3d::Identity();
  G = sigma * (sigma + Eigen::Matrix3d::Identity()).inverse();
  const Eigen::Vector3d x2 = predicted + G * (Eigen::Vector3d(2, 0, 0) - predicted);
  EXPECT_LT((x_hat[2] - x2).norm(), 1e-12);
}

TEST(OdometryEkf, DecayingProcessCovarianceIsEquationThirteen) {
  EXPECT_TRUE(decaying_process_diagonal(1, 1.5).isApprox(Eigen::Vector3d(150, 150, 15)));
  EXPECT_TRUE(decaying_process_diagonal(4, 2.0).isApprox(Eigen::Vector3d(150, 150, 15) / 16));
  EXPECT_TRUE(decaying_process_diagonal(9, 1.0).isApprox(Eigen::Vector3d(150, 150, 15) / 9));
}

// Reference poses built to satisfy eq. 12 exactly: x~_k = x^_{k-1} + phi_k c for arbitrary x^.
TEST(CircumferenceLs, RecoversExactParametersFromNoiseFreeRows) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Eigen::Vector2d c_true(1.9547, 1.9578);
  const double track = 1.6;
  WheelStream wheels;
  ReferenceTrajectory reference;
  std::vector<Pose2> x_hat;
  for (int k = 0; k < 500; ++k) {
    wheels.t_s.push_back(0.02 * k);
    wheels.rev_rl.push_back(k == 0 ? 0.0 : 0.4 + 0.1 * unit(rng));
    wheels.rev_rr.push_back(k == 0 ? 0.0 : 0.4 + 0.1 * unit(rng));
    x_hat.emplace_back(10 * unit(rng), 10 * unit(rng), 3 * unit(rng));
    Pose2 target = x_hat.back();
    if (k > 0) {
      const Pose2& previous = x_hat[static_cast<std::size_t>(k) - 1];
      const double n_l = wheels.rev_rl.back(), n_r = wheels.rev_rr.back();
      target = previous +
               Eigen::Vector3d((n_l * c_true(0) + n_r * c_true(1)) / 2 * std::cos(previous.z()),
                               (n_l * c_true(0) + n_r * c_true(1)) / 2 * std::sin(previous.z()),
                               (n_r * c_true(1) - n_l * c_true(0)) / track);
    }
    reference.poses.push_back(target);
  }
  for (int window : {1, 7, 10, 1000}) {
    const CircumferenceFit fit =
        fit_circumferences(wheels, reference, x_hat, track, Eigen::Vector3d(1, 1, 10), window);
    EXPECT_LT((fit.circumference_m - c_true).norm(), 1e-12) << window;
    EXPECT_LT(fit.residual_rms, 1e-12);
    EXPECT_GT(fit.condition_number, 1.0);
  }
}

TEST(CircumferenceLs, ReportsRankDeficiencyInsteadOfANumber) {
  WheelStream wheels{{0, 1, 2}, {0, 0, 0}, {0, 0, 0}, {}, {}, WheelUnit::kTicks, {}, {}, {}};
  ReferenceTrajectory reference;
  reference.poses = {Pose2::Zero(), Pose2::Zero(), Pose2::Zero()};
  const CircumferenceFit fit =
      fit_circumferences(wheels, reference, reference.poses, 1.6, Eigen::Vector3d(1, 1, 10));
  EXPECT_FALSE(std::isfinite(fit.condition_number));
  EXPECT_FALSE(fit.circumference_m.allFinite());
}

double consistent_fraction(const Log& log, const ReferenceTrajectory& reference) {
  int inside = 0;
  for (std::size_t i = 0; i < reference.poses.size(); ++i) {
    Eigen::Vector3d error = reference.poses[i] - log.truth->pose[reference.first_wheel_index + i];
    error.z() = wrap_angle(error.z());
    // chi-square with 3 degrees of freedom: 99.7 % below 14.16
    if (error.dot(reference.covariance[i].ldlt().solve(error)) < 14.16) ++inside;
  }
  return static_cast<double>(inside) / static_cast<double>(reference.poses.size());
}

// The reference with its times (the wheels' from its first sample), as trajectory_errors takes it.
PoseStream timed(const Log& log, const ReferenceTrajectory& reference) {
  const std::span<const double> t = reference.times(log.wheels);
  return {{t.begin(), t.end()}, reference.poses};
}

Log circuit_log() {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  scenario.route.laps = 1;
  return simulated_log(sim::simulate(scenario), /*with_truth=*/true);
}

TEST(ReferenceFilter, FusesToWellBelowTheGnssNoiseAndIsConsistent) {
  const Log log = circuit_log();
  ReferenceOptions options;
  const ReferenceTrajectory filter = compute_reference(log, options, ReferenceCovariance::kKeep);
  options.mode = ReferenceMode::kSmoother;
  const ReferenceTrajectory smoother = compute_reference(log, options, ReferenceCovariance::kKeep);
  const ReferencePath truth = reference_from_poses(*log.truth, "truth");
  const TrajectoryErrors filter_errors = trajectory_errors(timed(log, filter), truth);
  const TrajectoryErrors smoother_errors = trajectory_errors(timed(log, smoother), truth);
  EXPECT_LT(filter_errors.mean_position_m, 0.6);  // GNSS alone: 3 m per axis
  EXPECT_LT(filter_errors.mean_heading_rad, rad_from_deg(0.6));
  EXPECT_LT(smoother_errors.mean_position_m, 0.6 * filter_errors.mean_position_m);
  EXPECT_GT(consistent_fraction(log, filter), 0.98);
  EXPECT_GT(consistent_fraction(log, smoother), 0.98);
  EXPECT_EQ(filter.heading_source, "heading.csv");
  EXPECT_FALSE(log.vehicle.imu_position_m);  // the ideal IMU reads the rear axle's motion
}

TEST(ReferenceFilter, WorksWithoutImuAndHeadingFromTheGnssCourse) {
  Log log = circuit_log();
  log.imu.reset();
  log.heading.reset();
  const ReferenceTrajectory reference = compute_reference(log);
  EXPECT_EQ(reference.heading_source, "GNSS course");
  EXPECT_TRUE(reference.covariance.empty());  // not asked for
  const TrajectoryErrors errors =
      trajectory_errors(timed(log, reference), reference_from_poses(*log.truth, "truth"));
  EXPECT_LT(errors.mean_position_m, 2.0);
  EXPECT_LT(errors.mean_heading_rad, rad_from_deg(8.0));  // a coarse fallback: docs/calibration.md
}

// A gyro sample held until the next lags the turn by half a sample: the yaw would trail the truth
// by w dt / 2 (10 ms of yaw rate at 50 Hz). Read linear between its samples, it does not: the
// regression of the yaw error on the true yaw rate has no slope (noise-free IMU, ideal circuit).
TEST(ReferenceFilter, TheYawDoesNotLagTheGyrosTurn) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  scenario.route.laps = 1;
  scenario.imu.acc_sigma_mps2 = 0.0;
  scenario.imu.yaw_rate_sigma_radps = 0.0;
  const Log log = simulated_log(sim::simulate(scenario), /*with_truth=*/true);
  ReferenceOptions options;
  options.mode = ReferenceMode::kSmoother;
  const ReferenceTrajectory reference = compute_reference(log, options);
  const std::span<const double> times = reference.times(log.wheels);
  const PoseStream& truth = *log.truth;
  double error_rate = 0.0, rate_rate = 0.0;
  std::size_t j = 1;
  for (std::size_t i = 0; i < reference.poses.size(); ++i) {
    while (j + 1 < truth.size() && truth.t_s[j] < times[i]) ++j;
    if (j + 1 >= truth.size() || std::abs(truth.t_s[j] - times[i]) > 1e-9) continue;
    const double rate = angle_difference(truth.pose[j + 1].z(), truth.pose[j - 1].z()) /
                        (truth.t_s[j + 1] - truth.t_s[j - 1]);
    error_rate += angle_difference(reference.poses[i].z(), truth.pose[j].z()) * rate;
    rate_rate += rate * rate;
  }
  ASSERT_GT(rate_rate, 0.0);
  const double lag_s = -error_rate / rate_rate;  // held samples: 0.0107 s; linear: 0.0015 s
  EXPECT_LT(std::abs(lag_s), 0.003);
}

// One lap of the built-in urban drive (realistic), with its truth.
sim::Scenario urban_lap() {
  sim::Scenario scenario = load_scenario("urban");
  scenario.route.laps = 1;
  return scenario;
}

// The smoothed reference of `log` against its truth.
TrajectoryErrors smoothed_reference_errors(const Log& log, ReferenceOptions options = {}) {
  options.mode = ReferenceMode::kSmoother;
  return trajectory_errors(timed(log, compute_reference(log, options)),
                           reference_from_poses(*log.truth, "truth"));
}

// The realistic car's IMU sits at its centre of gravity, 1.45 m ahead of the rear axle whose
// pose the fixes give; vehicle.yaml says so. Taken as the axle's own, its readings put each turn's
// -w^2 x and dw/dt x into the axle's motion (measured on urban seeds 1-5: 0.32 m RMS against
// 0.22-0.24 m with the IMU where it is).
TEST(ReferenceFilter, TakesTheImuFromWhereVehicleYamlMountsItToTheRearAxle) {
  Log log = simulated_log(sim::simulate(urban_lap()), /*with_truth=*/true);
  ASSERT_TRUE(log.vehicle.imu_position_m);
  ASSERT_NEAR(log.vehicle.imu_position_m->x(), 1.45, 1e-12);
  const TrajectoryErrors mounted = smoothed_reference_errors(log);
  log.vehicle.imu_position_m.reset();
  const TrajectoryErrors at_axle = smoothed_reference_errors(log);
  EXPECT_LT(mounted.mean_position_m, 0.85 * at_axle.mean_position_m);
}

// A car's rear axle moves along its heading (the non-holonomic constraint): held to that while
// driving straight, the GNSS fixes' course steadies the yaw that heading.csv's 0.15 rad noise and
// the gyro's leave (measured on urban seeds 1-10, 2 laps: yaw RMS 5.3 mrad without, 3.8 with).
TEST(ReferenceFilter, HoldsTheRearAxlesVelocityAlongItsHeading) {
  const Log log = simulated_log(sim::simulate(urban_lap()), /*with_truth=*/true);
  const TrajectoryErrors held = smoothed_reference_errors(log);
  ReferenceOptions free_options;
  free_options.lateral_velocity_sigma_mps = 0.0;
  const TrajectoryErrors free = smoothed_reference_errors(log, free_options);
  EXPECT_LT(held.mean_heading_rad, 0.85 * free.mean_heading_rad);
  EXPECT_LT(held.mean_position_m, 1.05 * free.mean_position_m);
}

// An antenna on the roof, 1.5 m ahead of the rear axle and 0.4 m right of it, that vehicle.yaml
// states (gnss_x_m, gnss_y_m): layer 1 measures the axle through it. Taken as the axle's, the
// fixes swing out in every turn, and the held velocity turns that into heading (one urban lap).
TEST(ReferenceFilter, MeasuresTheAxleThroughTheAntennaWhereVehicleYamlStatesIt) {
  sim::Scenario scenario = urban_lap();
  scenario.gnss.lever_arm_x_m = 1.5;
  scenario.gnss.lever_arm_y_m = -0.4;
  scenario.gnss.lever_arm_stated = true;
  Log log = simulated_log(sim::simulate(scenario), /*with_truth=*/true);
  ASSERT_TRUE(log.vehicle.gnss_position_m);
  ASSERT_NEAR(log.vehicle.gnss_position_m->x(), 1.5, 1e-12);
  const TrajectoryErrors stated = smoothed_reference_errors(log);
  log.vehicle.gnss_position_m.reset();
  const TrajectoryErrors at_axle = smoothed_reference_errors(log);
  // Measured: 0.18 m and 2.8 mrad stated, 1.46 m and 5.1 mrad taken as the axle's.
  EXPECT_LT(stated.mean_position_m, 0.25 * at_axle.mean_position_m);
  EXPECT_LT(stated.mean_heading_rad, 0.7 * at_axle.mean_heading_rad);
}

}  // namespace
}  // namespace odocal
