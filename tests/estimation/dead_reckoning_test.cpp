// Dead reckoning, interpolation, start poses and error statistics against closed-form motion.

#include "odocal/estimation/dead_reckoning.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "odocal/error.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/start_pose.hpp"
#include "odocal/estimation/trajectory_errors.hpp"
#include "odocal/model/angle.hpp"

namespace odocal {
namespace {

constexpr double kRadius = 30.0;
constexpr double kSpeed = 5.0;
const OdometryParams kTrue{1.96, 1.95, 1.6};

// A vehicle on a CCW circle of radius kRadius around (0, kRadius), starting at the origin
// heading east: exact wheel increments and the closed-form pose at 50 Hz.
struct Circle {
  WheelStream wheels;
  PoseStream truth;
};

Circle make_circle(double duration_s) {
  Circle circle;
  const double rate = kSpeed / kRadius;
  for (int k = 0; k * 0.02 <= duration_s; ++k) {
    const double t = k * 0.02;
    const double angle = rate * t;
    circle.wheels.t_s.push_back(t);
    const double step = k == 0 ? 0.0 : rate * 0.02;
    circle.wheels.rev_rl.push_back((kRadius - kTrue.track_width_m / 2) * step /
                                   kTrue.circumference_rl_m);
    circle.wheels.rev_rr.push_back((kRadius + kTrue.track_width_m / 2) * step /
                                   kTrue.circumference_rr_m);
    circle.truth.t_s.push_back(t);
    circle.truth.pose.emplace_back(kRadius * std::sin(angle), kRadius * (1 - std::cos(angle)),
                                   angle);
  }
  return circle;
}

// The sampled model's only error on a circle is its radius excess R dtheta^2 / 24 (see
// odometry_model_test), so positions stay within twice that of the true circle.
constexpr double kStepYaw = kSpeed / kRadius * 0.02;
constexpr double kDiscretisationBound_m = 2.0 * kRadius * kStepYaw * kStepYaw / 24 * 1.01;

TEST(DeadReckoning, FollowsTheClosedFormCircleWithTrueParameters) {
  const Circle circle = make_circle(60.0);
  const PoseStream trajectory = dead_reckon(circle.wheels, kTrue, Pose2::Zero());
  const TrajectoryErrors errors =
      trajectory_errors(trajectory, reference_from_poses(circle.truth, "truth"));
  EXPECT_LT(errors.max_position_m, kDiscretisationBound_m);
  EXPECT_LT(errors.max_heading_rad, 1e-12);
  EXPECT_NEAR(errors.distance_m, kSpeed * 60.0, 1e-3);  // polyline chords: slightly short
  EXPECT_EQ(errors.position_samples, circle.truth.size());
}

// A 1 mm smaller right circumference turns the vehicle right by (c_RR - c'_RR) n_RR / t_R.
TEST(DeadReckoning, WrongCircumferenceDriftsAsPredicted) {
  const Circle circle = make_circle(20.0);
  OdometryParams wrong = kTrue;
  wrong.circumference_rr_m -= 0.001;
  const PoseStream trajectory = dead_reckon(circle.wheels, wrong, Pose2::Zero());
  double revs_rr = 0.0;
  for (double n : circle.wheels.rev_rr) revs_rr += n;
  const double expected_heading_error = 0.001 * revs_rr / kTrue.track_width_m;
  EXPECT_NEAR(circle.truth.pose.back().z() - trajectory.pose.back().z(), expected_heading_error,
              1e-12);
  const TrajectoryErrors errors =
      trajectory_errors(trajectory, reference_from_poses(circle.truth, "truth"));
  EXPECT_NEAR(errors.max_heading_rad, expected_heading_error, 1e-9);
  EXPECT_GT(errors.final_drift_percent, 0.0);
}

TEST(Interpolation, PoseTakesTheShortArcAcrossPi) {
  PoseStream poses;
  poses.t_s = {0.0, 1.0};
  poses.pose = {Pose2(0, 0, std::numbers::pi - 0.1), Pose2(2, 4, -std::numbers::pi + 0.1)};
  const auto middle = interpolate_pose(poses, 0.5);
  ASSERT_TRUE(middle);
  EXPECT_DOUBLE_EQ(middle->x(), 1.0);
  EXPECT_DOUBLE_EQ(middle->y(), 2.0);
  EXPECT_NEAR(std::abs(wrap_angle(middle->z())), std::numbers::pi, 1e-12);
  EXPECT_FALSE(interpolate_pose(poses, 1.0001));
  EXPECT_FALSE(interpolate_pose(poses, -0.1));
  EXPECT_TRUE(interpolate_pose(poses, 1.0));
}

TEST(StartPose, FromTruthInterpolates) {
  const Circle circle = make_circle(2.0);
  const Pose2 start = start_pose_from_truth(circle.truth, 0.01);
  EXPECT_NEAR(start.x(), kSpeed * 0.01, 1e-4);
  EXPECT_THROW(start_pose_from_truth(circle.truth, -1.0), InsufficientDataError);
}

// A log of the circle with 10 Hz GNSS fixes carrying a fixed pseudo-random error.
Log circle_log(const Circle& circle, double gnss_error_m) {
  Log log;
  log.wheels = circle.wheels;
  std::mt19937 rng(11);
  std::normal_distribution<double> unit(0.0, 1.0);  // times the error: a sigma of 0 is allowed
  const auto noise = [&](std::mt19937& g) { return gnss_error_m * unit(g); };
  for (std::size_t k = 0; k < circle.truth.size(); k += 5) {
    log.gnss.t_s.push_back(circle.truth.t_s[k]);
    log.gnss.x_m.push_back(circle.truth.pose[k].x() + noise(rng));
    log.gnss.y_m.push_back(circle.truth.pose[k].y() + noise(rng));
  }
  return log;
}

TEST(StartPose, FromGnssAlignsOdometryOnATightCircle) {
  const Circle circle = make_circle(20.0);
  // Exact fixes: the rigid alignment returns the true start (heading east at the origin).
  Pose2 start = start_pose_from_gnss(circle_log(circle, 0.0), kTrue);
  EXPECT_LT(start.head<2>().norm(), 1e-3);
  EXPECT_LT(std::abs(start.z()), 1e-4);
  // 3 m noise on 100 fixes spread ~15 m around their centroid: sigma ~ 0.3 m and ~0.02 rad.
  start = start_pose_from_gnss(circle_log(circle, 3.0), kTrue);
  EXPECT_LT(start.head<2>().norm(), 1.2);
  EXPECT_LT(std::abs(start.z()), 0.08);
}

// The fixes of an antenna 1.5 m ahead and 0.4 m right of the axle, which vehicle.yaml states: the
// start is the axle's, not the antenna's.
TEST(StartPose, FromGnssTakesAStatedAntennaBackToTheAxle) {
  const Circle circle = make_circle(20.0);
  const Eigen::Vector2d antenna(1.5, -0.4);
  Log log = circle_log(circle, 0.0);
  for (std::size_t k = 0; k < log.gnss.size(); ++k) {
    const Pose2 pose = *interpolate_pose(circle.truth, log.gnss.t_s[k]);
    const Eigen::Vector2d at = pose.head<2>() + Eigen::Rotation2Dd(pose.z()) * antenna;
    log.gnss.x_m[k] = at.x();
    log.gnss.y_m[k] = at.y();
  }
  log.vehicle.gnss_position_m = antenna;
  Pose2 start = start_pose_from_gnss(log, kTrue);
  EXPECT_LT(start.head<2>().norm(), 1e-3);
  EXPECT_LT(std::abs(start.z()), 1e-4);
  log.vehicle.gnss_position_m.reset();  // taken as the axle's: the start lands near the antenna
  start = start_pose_from_gnss(log, kTrue);
  EXPECT_GT(start.head<2>().norm(), 1.0);
}

TEST(StartPose, StandingStillFallsBackToTheHeadingStream) {
  Circle still = make_circle(3.0);
  std::fill(still.wheels.rev_rl.begin(), still.wheels.rev_rl.end(), 0.0);
  std::fill(still.wheels.rev_rr.begin(), still.wheels.rev_rr.end(), 0.0);
  Log log = circle_log(still, 0.0);
  for (double& x : log.gnss.x_m) x = 7.0;
  for (double& y : log.gnss.y_m) y = -2.0;
  EXPECT_THROW(start_pose_from_gnss(log, kTrue), InsufficientDataError);

  // Heading turning at 0.2 rad/s through +-pi: the line fit recovers the value at t = 0.
  log.heading.emplace();
  for (int k = 0; k <= 20; ++k) {
    log.heading->t_s.push_back(0.1 * k);
    log.heading->heading_rad.push_back(wrap_angle(3.0 + 0.2 * 0.1 * k));
  }
  const Pose2 start = start_pose_from_gnss(log, kTrue);
  EXPECT_NEAR(start.x(), 7.0, 1e-12);
  EXPECT_NEAR(start.y(), -2.0, 1e-12);
  EXPECT_NEAR(start.z(), 3.0, 1e-9);
}

TEST(TrajectoryErrors, AgainstGnssWithoutHeadingReportsNoHeadingSamples) {
  const Circle circle = make_circle(5.0);
  GnssStream gnss;
  gnss.t_s = {1.0, 2.0, 100.0};  // the last fix lies outside the trajectory and is skipped
  gnss.x_m = {circle.truth.pose[50].x() + 3.0, circle.truth.pose[100].x(), 0.0};
  gnss.y_m = {circle.truth.pose[50].y() + 4.0, circle.truth.pose[100].y(), 0.0};
  const PoseStream trajectory = dead_reckon(circle.wheels, kTrue, Pose2::Zero());
  const TrajectoryErrors errors = trajectory_errors(trajectory, reference_from_gnss(gnss, nullptr));
  EXPECT_EQ(errors.position_samples, 2u);
  EXPECT_EQ(errors.heading_samples, 0u);
  EXPECT_NEAR(errors.mean_position_m, 2.5, kDiscretisationBound_m);
  EXPECT_NEAR(errors.max_position_m, 5.0, kDiscretisationBound_m);
  EXPECT_NEAR(errors.final_position_m, 0.0, kDiscretisationBound_m);
}

TEST(TrajectoryErrors, NoOverlapIsAnError) {
  const Circle circle = make_circle(1.0);
  GnssStream gnss{{50.0}, {0.0}, {0.0}, {}, {}, {}, std::nullopt};
  const PoseStream trajectory = dead_reckon(circle.wheels, kTrue, Pose2::Zero());
  EXPECT_THROW(trajectory_errors(trajectory, reference_from_gnss(gnss, nullptr)), Error);
}

}  // namespace
}  // namespace odocal
