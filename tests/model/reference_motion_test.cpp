// Layer 1's motion and measurement models: analytic Jacobians against central differences (at
// zero, near zero and at random states), and the motion model against closed-form motion.

#include "odocal/model/reference_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
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
    const ImuSample imu{5 * u(rng), 5 * u(rng), 0.8 * u(rng)};
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
    ReferenceRowJacobian J_speed, J_yaw;
    reference_speed(x, &J_speed);
    reference_yaw(x, &J_yaw);
    const auto speed = [](const ReferenceState& s) {
      return Eigen::Matrix<double, 1, 1>(reference_speed(s));
    };
    const auto yaw = [](const ReferenceState& s) {
      return Eigen::Matrix<double, 1, 1>(reference_yaw(s));
    };
    EXPECT_LT((J_speed - numerical_jacobian<1, 8>(speed, x)).norm(), 1e-8);
    EXPECT_LT((J_yaw - numerical_jacobian<1, 8>(yaw, x)).norm(), 1e-9);
  }
}

}  // namespace
}  // namespace odocal
