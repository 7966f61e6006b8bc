// Layer 1's motion and measurement models: analytic Jacobians against central differences (at
// zero, near zero and at random states), and the motion model against closed-form motion.

#include "odocal/model/reference_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "../support/numerical_jacobian.hpp"

namespace odocal {
namespace {

using testing::numerical_jacobian;

void expect_motion_jacobian_matches(const ReferenceState& x, const ImuSample& imu, double dt) {
  ReferenceJacobian J;
  predict_reference(x, imu, dt, &J);
  const auto f = [&](const ReferenceState& state) { return predict_reference(state, imu, dt); };
  const ReferenceJacobian numeric = numerical_jacobian<8, 8>(f, x);
  EXPECT_LT((J - numeric).cwiseAbs().maxCoeff(), 1e-8) << "analytic\n"
                                                       << J << "\nnumeric\n"
                                                       << numeric;
}

TEST(ReferenceMotion, JacobianMatchesNumericalAtZeroNearZeroAndRandomStates) {
  expect_motion_jacobian_matches(ReferenceState::Zero(), {}, 0.02);
  ReferenceState tiny = ReferenceState::Constant(1e-9);
  expect_motion_jacobian_matches(tiny, {1e-9, -1e-9, 1e-9}, 0.02);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    ReferenceState x;
    x << 100 * u(rng), 100 * u(rng), 30 * u(rng), 30 * u(rng), 4 * u(rng), 0.5 * u(rng),
        0.5 * u(rng), 0.05 * u(rng);
    ImuSample imu{5 * u(rng), 5 * u(rng), 0.8 * u(rng)};
    for (const double dt : {0.001, 0.02, 0.5}) expect_motion_jacobian_matches(x, imu, dt);
    imu.wz_dot_radps2 = 2 * u(rng);  // an IMU off the reference point
    imu.lever_arm_m = Eigen::Vector2d(2 * u(rng), 0.5 * u(rng));
    for (const double dt : {0.001, 0.02, 0.5}) expect_motion_jacobian_matches(x, imu, dt);
  }
}

TEST(ReferenceMotion, TheGyroBiasReachesPositionAndVelocityThroughTheMidpointHeading) {
  // A vehicle accelerating forward: a gyro bias tilts the midpoint heading by -b dt / 2, which
  // turns the acceleration sideways. The bias column must carry it (it once did not).
  ReferenceState x = ReferenceState::Zero();
  x(2) = 20.0;
  const double dt = 0.02, a = 3.0;
  ReferenceJacobian J;
  predict_reference(x, {a, 0.0, 0.0}, dt, &J);
  EXPECT_NEAR(J(1, 7), -0.25 * dt * dt * dt * a, 1e-15);  // d y / d b_gyro
  EXPECT_NEAR(J(3, 7), -0.5 * dt * dt * a, 1e-15);        // d vy / d b_gyro
  EXPECT_EQ(J(4, 7), -dt);
}

TEST(ReferenceMotion, ConstantAccelerationAlongTheHeadingIsExact) {
  ReferenceState x = ReferenceState::Zero();
  const double yaw = 0.7, v0 = 5.0, a = 1.5, dt = 0.01;
  x << 10.0, -3.0, v0 * std::cos(yaw), v0 * std::sin(yaw), yaw, 0.0, 0.0, 0.0;
  const ReferenceState start = x;
  for (int k = 0; k < 500; ++k) x = predict_reference(x, {a, 0.0, 0.0}, dt);
  const double t = 500 * dt, along = v0 * t + 0.5 * a * t * t;
  EXPECT_NEAR(x(0), start(0) + along * std::cos(yaw), 1e-9);
  EXPECT_NEAR(x(1), start(1) + along * std::sin(yaw), 1e-9);
  EXPECT_NEAR(std::hypot(x(2), x(3)), v0 + a * t, 1e-12);
  EXPECT_DOUBLE_EQ(x(4), yaw);
}

// The rear axle on a circle of radius R at speed v, the IMU l ahead of it: the IMU's own circle
// is wider and its acceleration points at the centre, (-w^2 l, v w) in the body frame. Taken at
// the IMU's place, the reference point stays on the axle's circle; taken as the point's own, the
// forward -w^2 l brakes it.
TEST(ReferenceMotion, AnImuAheadOfThePointIsTakenToThePoint) {
  const double radius = 10.0, v = 5.0, w = v / radius, l = 1.45, dt = 0.01;
  const auto drive = [&](const Eigen::Vector2d& stated_lever_arm) {
    ReferenceState x = ReferenceState::Zero();
    x(2) = v;
    ImuSample imu{-w * w * l, v * w, w};
    imu.lever_arm_m = stated_lever_arm;
    for (int k = 0; k < 300; ++k) x = predict_reference(x, imu, dt);
    const double t = 300 * dt;
    return Eigen::Vector2d(x(0) - radius * std::sin(w * t), x(1) - radius * (1.0 - std::cos(w * t)))
        .norm();
  };
  EXPECT_LT(drive(Eigen::Vector2d(l, 0.0)), 0.01);
  EXPECT_GT(drive(Eigen::Vector2d::Zero()), 0.5);
}

// A robot pivoting about the reference point, its yaw rate swelling and fading: an IMU l ahead
// reads -w^2 l forward and dw/dt l to the left, and the point itself does not move. The rate's
// change is the sample's forward difference, as the filter holds it.
TEST(ReferenceMotion, APivotAboutThePointLeavesItWhereItIs) {
  const double l = 0.8, dt = 0.02;
  const auto rate = [](double t) { return 1.5 * std::sin(0.5 * t); };
  const auto drive = [&](double stated_l) {
    ReferenceState x = ReferenceState::Zero();
    for (int k = 0; k < 300; ++k) {
      const double t = k * dt, w = rate(t);
      const double w_dot = (rate(t + dt) - w) / dt;
      ImuSample imu{-w * w * l, 0.75 * std::cos(0.5 * t) * l, w, w_dot};
      imu.lever_arm_m = Eigen::Vector2d(stated_l, 0.0);
      x = predict_reference(x, imu, dt);
    }
    return x.head<2>().norm();
  };
  EXPECT_LT(drive(l), 0.02);
  EXPECT_GT(drive(0.0), 0.15);
}

TEST(ReferenceMotion, BiasesAreSubtractedFromTheImu) {
  ReferenceState x = ReferenceState::Zero();
  x.tail<3>() << 0.2, -0.1, 0.01;  // the IMU reads exactly its biases: the vehicle stands still
  const ReferenceState next = predict_reference(x, {0.2, -0.1, 0.01}, 0.1);
  EXPECT_LT((next - x).norm(), 1e-15);
}

TEST(ReferenceMeasurements, JacobiansMatchNumerical) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    ReferenceState x;
    for (int i = 0; i < kReferenceStates; ++i) x(i) = 10 * u(rng);
    Eigen::Matrix<double, 2, kReferenceStates> J_position;
    reference_position(x, &J_position);
    EXPECT_LT((J_position - numerical_jacobian<2, 8>(
                                [](const ReferenceState& s) { return reference_position(s); }, x))
                  .norm(),
              1e-9);
    ReferenceRowJacobian J_speed, J_yaw, J_lateral;
    reference_speed(x, &J_speed);
    reference_lateral_velocity(x, &J_lateral);
    reference_yaw(x, &J_yaw);
    const auto speed = [](const ReferenceState& s) {
      return Eigen::Matrix<double, 1, 1>(reference_speed(s));
    };
    const auto yaw = [](const ReferenceState& s) {
      return Eigen::Matrix<double, 1, 1>(reference_yaw(s));
    };
    EXPECT_LT((J_speed - numerical_jacobian<1, 8>(speed, x)).norm(), 1e-8);
    EXPECT_LT((J_yaw - numerical_jacobian<1, 8>(yaw, x)).norm(), 1e-9);
    const auto lateral = [](const ReferenceState& s) {
      return Eigen::Matrix<double, 1, 1>(reference_lateral_velocity(s));
    };
    EXPECT_LT((J_lateral - numerical_jacobian<1, 8>(lateral, x)).norm(), 1e-8);

    const Eigen::Vector2d antenna(2 * u(rng), u(rng));
    const double gyro = 0.3 * u(rng);
    Eigen::Matrix<double, 2, kReferenceStates> J_antenna;
    reference_antenna_position(x, antenna, &J_antenna);
    const auto antenna_position = [&](const ReferenceState& s) {
      return reference_antenna_position(s, antenna);
    };
    EXPECT_LT((J_antenna - numerical_jacobian<2, 8>(antenna_position, x)).norm(), 1e-8);
    ReferenceRowJacobian J_antenna_speed;
    reference_antenna_speed(x, antenna, gyro, &J_antenna_speed);
    const auto antenna_speed = [&](const ReferenceState& s) {
      return Eigen::Matrix<double, 1, 1>(reference_antenna_speed(s, antenna, gyro));
    };
    EXPECT_LT((J_antenna_speed - numerical_jacobian<1, 8>(antenna_speed, x)).norm(), 1e-8);
  }
}

TEST(ReferenceMeasurements, AnAntennaOffTheAxleIsWhereTheHeadingTurnsIt) {
  ReferenceState x = ReferenceState::Zero();
  x.head<2>() << 10.0, 20.0;
  x(4) = 0.5 * std::numbers::pi;  // pointing north: ahead is north, left is west
  const Eigen::Vector2d antenna(1.5, 0.5);
  EXPECT_LT((reference_antenna_position(x, antenna) - Eigen::Vector2d(9.5, 21.5)).norm(), 1e-12);
  EXPECT_LT((reference_antenna_position(x, Eigen::Vector2d::Zero()) - reference_position(x)).norm(),
            1e-15);
}

TEST(ReferenceMeasurements, AnAntennaOffTheAxleRunsTheTurnsSpeedBesideTheAxles) {
  ReferenceState x = ReferenceState::Zero();
  x(2) = 10.0;  // east at 10 m/s, pointing east, turning left at 0.1 rad/s (gyro 0.12, bias 0.02)
  x(7) = 0.02;
  const Eigen::Vector2d antenna(1.5, 0.5);
  // 0.5 m left runs 0.05 m/s slower; 1.5 m ahead swings out at 0.15 m/s.
  EXPECT_NEAR(reference_antenna_speed(x, antenna, 0.12), std::hypot(9.95, 0.15), 1e-12);
  x(2) = 0.0;  // a pivot on the spot: the antenna circles at 0.1 |l|
  EXPECT_NEAR(reference_antenna_speed(x, antenna, 0.12), 0.1 * antenna.norm(), 1e-12);
  x(2) = 10.0;
  EXPECT_NEAR(reference_antenna_speed(x, Eigen::Vector2d::Zero(), 0.12), reference_speed(x), 1e-15);
}

TEST(ReferenceMeasurements, TheLateralVelocityIsTheVelocityAcrossTheHeading) {
  ReferenceState x = ReferenceState::Zero();
  x(2) = 3.0;                     // moving east at 3 m/s ...
  x(4) = 0.5 * std::numbers::pi;  // ... while pointing north: 3 m/s to the right
  EXPECT_NEAR(reference_lateral_velocity(x), -3.0, 1e-12);
  x(4) = 0.0;
  EXPECT_NEAR(reference_lateral_velocity(x), 0.0, 1e-12);
}

}  // namespace
}  // namespace odocal
