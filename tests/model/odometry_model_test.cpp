// The two-wheel odometry model (paper eqs. 1-2): analytic Jacobians against numerical ones, and
// the integrated model against closed-form straight-line and circle motion.

#include "odocal/model/odometry_model.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "../support/numerical_jacobian.hpp"
#include "odocal/model/angle.hpp"

namespace odocal {
namespace {

using testing::numerical_jacobian;

struct JacobianCase {
  Pose2 pose;
  WheelIncrement n;
  OdometryParams params;
  double side_slip_rad;
};

void expect_jacobians_match(const JacobianCase& c) {
  OdometryJacobianPose J_pose;
  OdometryJacobianWheels J_wheels;
  OdometryJacobianParams J_params;
  OdometryJacobianSideSlip J_slip;
  predict_pose(c.pose, c.n, c.params, c.side_slip_rad, {&J_pose, &J_wheels, &J_params, &J_slip});

  const auto f_pose = [&](const Eigen::Vector3d& pose) {
    return predict_pose(pose, c.n, c.params, c.side_slip_rad);
  };
  const auto f_wheels = [&](const Eigen::Vector2d& n) {
    return predict_pose(c.pose, {n[0], n[1]}, c.params, c.side_slip_rad);
  };
  const auto f_params = [&](const Eigen::Vector3d& p) {
    return predict_pose(c.pose, c.n, {p[0], p[1], p[2]}, c.side_slip_rad);
  };
  const auto f_slip = [&](const Eigen::Matrix<double, 1, 1>& beta) {
    return predict_pose(c.pose, c.n, c.params, beta[0]);
  };
  const Eigen::Vector3d p(c.params.circumference_rl_m, c.params.circumference_rr_m,
                          c.params.track_width_m);
  constexpr double kTol = 1e-7;
  EXPECT_LT((J_pose - numerical_jacobian<3, 3>(f_pose, c.pose)).norm(), kTol);
  EXPECT_LT((J_wheels - numerical_jacobian<3, 2>(f_wheels, Eigen::Vector2d(c.n.rev_rl, c.n.rev_rr)))
                .norm(),
            kTol);
  EXPECT_LT((J_params - numerical_jacobian<3, 3>(f_params, p)).norm(), kTol);
  EXPECT_LT(
      (J_slip - numerical_jacobian<3, 1>(f_slip, Eigen::Matrix<double, 1, 1>(c.side_slip_rad)))
          .norm(),
      kTol);
}

const OdometryParams kParams{1.964, 1.962, 1.6};

TEST(OdometryModelJacobians, MatchNumericalAtZeroMotion) {
  expect_jacobians_match({Pose2(0, 0, 0), {0.0, 0.0}, kParams, 0.0});
}

TEST(OdometryModelJacobians, MatchNumericalNearZeroMotion) {
  expect_jacobians_match({Pose2(1e-3, -2e-3, 1e-4), {1e-6, -1e-6}, kParams, 1e-5});
}

TEST(OdometryModelJacobians, MatchNumericalAtRandomPoints) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int i = 0; i < 200; ++i) {
    const Pose2 pose(100 * unit(rng), 100 * unit(rng), 4 * unit(rng));
    const WheelIncrement n{0.5 * unit(rng), 0.5 * unit(rng)};
    const OdometryParams params{2.0 + 0.1 * unit(rng), 2.0 + 0.1 * unit(rng),
                                1.6 + 0.2 * unit(rng)};
    expect_jacobians_match({pose, n, params, 0.05 * unit(rng)});
  }
}

TEST(OdometryModel, StraightLineMovesAlongTheHeading) {
  const double heading = 0.7;
  Pose2 pose(3.0, -1.0, heading);
  const WheelIncrement n{0.1, 0.1};
  for (int k = 0; k < 500; ++k) pose = predict_pose(pose, n, {2.0, 2.0, 1.6});
  const double distance = 500 * 0.1 * 2.0;
  EXPECT_NEAR(pose.x(), 3.0 + distance * std::cos(heading), 1e-9);
  EXPECT_NEAR(pose.y(), -1.0 + distance * std::sin(heading), 1e-9);
  EXPECT_DOUBLE_EQ(pose.z(), heading);
}

// Constant wheel increments: each step has length ds along the midpoint heading, so the poses
// lie exactly on a circle whose chord per step is ds: radius rho = (ds / dtheta) (dtheta / 2) /
// sin(dtheta / 2), slightly larger than the wheels' turning radius ds / dtheta.
TEST(OdometryModel, ConstantIncrementsTraceTheClosedFormCircle) {
  const double radius_m = 25.0;
  const OdometryParams params{1.97, 1.95, 1.58};
  const double step_rad = 0.01;
  const WheelIncrement n{
      (radius_m - params.track_width_m / 2) * step_rad / params.circumference_rl_m,
      (radius_m + params.track_width_m / 2) * step_rad / params.circumference_rr_m};
  const double rho_m = radius_m * (step_rad / 2) / std::sin(step_rad / 2);
  Pose2 pose(0.0, 0.0, 0.0);
  const int steps = 1000;
  for (int k = 1; k <= steps; ++k) {
    pose = predict_pose(pose, n, params);
    // Chord k ends at the polar angle k dtheta around the centre (0, rho) seen from the start.
    const double angle = k * step_rad;
    ASSERT_NEAR(pose.x(), rho_m * std::sin(angle), 1e-9) << k;
    ASSERT_NEAR(pose.y(), rho_m * (1.0 - std::cos(angle)), 1e-9) << k;
    ASSERT_NEAR(pose.z(), angle, 1e-12);
  }
  // The model's radius error is second order in the yaw step: R dtheta^2 / 24.
  EXPECT_NEAR(rho_m - radius_m, radius_m * step_rad * step_rad / 24, 1e-9);
}

TEST(OdometryModel, ReversingRetracesTheCircle) {
  const OdometryParams params{2.0, 2.0, 1.6};
  Pose2 pose(0, 0, 0.3);
  for (int k = 0; k < 100; ++k) pose = predict_pose(pose, {0.05, 0.07}, params);
  for (int k = 0; k < 100; ++k) pose = predict_pose(pose, {-0.05, -0.07}, params);
  EXPECT_LT((pose - Pose2(0, 0, 0.3)).norm(), 1e-9);
}

TEST(OdometryModel, BodyIncrementFollowsEquationTwo) {
  const BodyIncrement step = body_increment({0.3, 0.5}, {2.0, 1.9, 1.6});
  EXPECT_DOUBLE_EQ(step.distance_m, (0.3 * 2.0 + 0.5 * 1.9) / 2);
  EXPECT_DOUBLE_EQ(step.yaw_rad, (0.5 * 1.9 - 0.3 * 2.0) / 1.6);
}

TEST(OdometryModel, SideSlipRotatesTheStepOnly) {
  const Pose2 pose = predict_pose(Pose2(0, 0, 0), {0.5, 0.5}, {2.0, 2.0, 1.6}, 0.1);
  // 0.5 rev of a 2 m wheel on both sides: 1 m along heading 0 + beta.
  EXPECT_NEAR(pose.x(), std::cos(0.1), 1e-12);
  EXPECT_NEAR(pose.y(), std::sin(0.1), 1e-12);
  EXPECT_DOUBLE_EQ(pose.z(), 0.0);
}

TEST(Angle, WrapsIntoHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(wrap_angle(std::numbers::pi), std::numbers::pi);
  EXPECT_DOUBLE_EQ(wrap_angle(-std::numbers::pi), std::numbers::pi);
  EXPECT_NEAR(wrap_angle(3 * std::numbers::pi + 0.1), -std::numbers::pi + 0.1, 1e-12);
  EXPECT_NEAR(angle_difference(0.1, 2 * std::numbers::pi - 0.1), 0.2, 1e-12);
}

}  // namespace
}  // namespace odocal
