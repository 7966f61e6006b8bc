// Pre-integrated odometry against dead reckoning, numerical parameter Jacobians, and a
// Monte-Carlo covariance of noisy wheel increments.

#include "odocal/estimation/odometry_preintegration.hpp"

#include <gtest/gtest.h>

#include <random>

#include "../support/numerical_jacobian.hpp"
#include "odocal/estimation/dead_reckoning.hpp"
#include "odocal/estimation/driving_state.hpp"

namespace odocal {
namespace {

WheelStream curving_wheels() {
  WheelStream wheels;
  for (int k = 0; k <= 120; ++k) {
    wheels.t_s.push_back(0.02 * k);
    const double turn = k < 60 ? 0.01 : -0.004;
    wheels.rev_rl.push_back(k == 0 ? 0.0 : 0.2 - turn);
    wheels.rev_rr.push_back(k == 0 ? 0.0 : 0.2 + turn);
  }
  return wheels;
}

TEST(OdometryPreintegration, IsDeadReckoningFromTheFirstKeyframe) {
  const WheelStream wheels = curving_wheels();
  const OdometryParams params{1.95, 1.96, 1.6};
  const PreintegratedSegment segment = preintegrate(wheels, 20, 110, params, {});
  WheelStream tail = wheels;  // samples 20..110 with sample 20 as the start
  tail.t_s.assign(wheels.t_s.begin() + 20, wheels.t_s.begin() + 111);
  tail.rev_rl.assign(wheels.rev_rl.begin() + 20, wheels.rev_rl.begin() + 111);
  tail.rev_rr.assign(wheels.rev_rr.begin() + 20, wheels.rev_rr.begin() + 111);
  tail.rev_rl[0] = tail.rev_rr[0] = 0.0;
  const PoseStream path = dead_reckon(tail, params, Pose2::Zero());
  ASSERT_EQ(segment.delta.size(), path.size());
  for (std::size_t s = 0; s < path.size(); ++s)
    EXPECT_LT((segment.delta[s] - path.pose[s]).norm(), 1e-12) << s;
}

TEST(OdometryPreintegration, ParameterJacobianMatchesNumerical) {
  const WheelStream wheels = curving_wheels();
  const Eigen::Vector3d at(1.95, 1.96, 1.6);
  const PreintegratedSegment segment = preintegrate(wheels, 0, 120, {at(0), at(1), at(2)}, {});
  for (const std::size_t s : {1ul, 37ul, 120ul}) {
    const auto numerical = testing::numerical_jacobian<3, 3>(
        [&](const Eigen::Vector3d& p) -> Eigen::Vector3d {
          return preintegrate(wheels, 0, 120, {p(0), p(1), p(2)}, {}).delta[s];
        },
        at);
    EXPECT_LT((segment.J_delta_params[s] - numerical).cwiseAbs().maxCoeff(), 1e-7) << s;
  }
}

// Driving states that exercise every regressor: speed, both turn directions, acceleration
// and braking (the accelerometer's specific force a little off the wheels' acceleration).
std::vector<DrivingState> varied_states(std::size_t count) {
  std::vector<DrivingState> states(count);
  for (std::size_t k = 0; k < count; ++k) {
    const double phase = 0.1 * static_cast<double>(k);
    const double a_x = 2.5 * std::sin(1.3 * phase), a_y = 4.0 * std::cos(0.7 * phase);
    const double speed = 10.0 + 3.0 * std::sin(phase);
    states[k].speed_mps = static_cast<float>(speed);
    states[k].longitudinal_mps2 = static_cast<float>(a_x);
    states[k].yaw_rate_radps = static_cast<float>(a_y / speed);
    states[k].specific_force_x_mps2 = static_cast<float>(a_x + 0.3);
    states[k].specific_force_y_mps2 = static_cast<float>(0.9 * a_y);
  }
  return states;
}

TEST(OdometryPreintegration, TyreJacobianMatchesNumerical) {
  const WheelStream wheels = curving_wheels();
  const std::vector<DrivingState> states = varied_states(wheels.size());
  const OdometryParams params{1.95, 1.96, 1.6};
  const TyreModel::Vector at =
      TyreModel{2e-6, 3e-4, 8e-3, -2e-3, -5e-3, 6e-4, 4e-4, 2e-3, 0.05, 0.02, -5e-3}.coefficients();
  const VehicleBody body;
  const TyreConditions tyre{states, TyreModel::from(at), body};
  const PreintegratedSegment segment = preintegrate(wheels, 0, 120, params, {}, &tyre);
  ASSERT_EQ(segment.J_delta_tyre.size(), segment.delta.size());
  for (const std::size_t s : {1ul, 37ul, 120ul}) {
    const auto numerical = testing::numerical_jacobian<3, TyreModel::kCoefficients>(
        [&](const TyreModel::Vector& k) -> Eigen::Vector3d {
          const TyreConditions moved{states, TyreModel::from(k), body};
          return preintegrate(wheels, 0, 120, params, {}, &moved).delta[s];
        },
        at);
    EXPECT_LT((segment.J_delta_tyre[s] - numerical).cwiseAbs().maxCoeff(),
              1e-6 * std::max(1.0, numerical.cwiseAbs().maxCoeff()))
        << s;
  }
}

TEST(OdometryPreintegration, TyreModelIsDeadReckoningOfTheScaledIncrements) {
  const WheelStream wheels = curving_wheels();
  const std::vector<DrivingState> states = varied_states(wheels.size());
  const OdometryParams params{1.95, 1.96, 1.6};
  const TyreModel model{2e-6, 3e-4, 8e-3, 2e-3, -5e-3};
  const TyreConditions tyre{states, model, VehicleBody{}};
  const PreintegratedSegment segment = preintegrate(wheels, 0, 120, params, {}, &tyre);
  // Independent: each increment scaled by hand with the formula of tyre_model.hpp.
  WheelStream scaled = wheels;
  for (std::size_t k = 0; k < wheels.size(); ++k) {
    const DrivingState& x = states[k];
    const double common = 1.0 + 2e-6 * x.speed_mps * x.speed_mps -
                          (x.longitudinal_mps2 > 0 ? 8e-3 : 2e-3) * x.longitudinal_mps2 -
                          5e-3 * x.yaw_rate_radps * x.yaw_rate_radps;
    scaled.rev_rl[k] *= common + 3e-4 * x.lateral_mps2();
    scaled.rev_rr[k] *= common - 3e-4 * x.lateral_mps2();
  }
  const PoseStream path = dead_reckon(scaled, params, Pose2::Zero());
  EXPECT_LT((segment.delta.back() - path.pose.back()).norm(), 1e-12);
  EXPECT_GT((segment.delta.back() - dead_reckon(wheels, params, Pose2::Zero()).pose.back()).norm(),
            1e-3);
}

TEST(OdometryPreintegration, SideSlipIsDeadReckoningAlongTheSlippedCourse) {
  // beta = k f_y turns every step's course (eq. 1's beta); dead reckoning a stream that carries
  // the same side slip per sample (by hand here) lands on the same pose.
  const WheelStream wheels = curving_wheels();
  const std::vector<DrivingState> states = varied_states(wheels.size());
  const OdometryParams params{1.95, 1.96, 1.6};
  TyreModel model;
  model.k_side_slip_s2pm = -5e-3;
  EXPECT_DOUBLE_EQ(tyre_factor(model, states[3], RearWheel::kLeft, VehicleBody{}), 1.0);
  const TyreConditions tyre{states, model, VehicleBody{}};
  const PreintegratedSegment segment = preintegrate(wheels, 0, 120, params, {}, &tyre);
  WheelStream slipping = wheels;
  for (const DrivingState& x : states)
    slipping.side_slip_rad.push_back(static_cast<float>(-5e-3 * x.specific_force_y_mps2));
  const PoseStream path = dead_reckon(slipping, params, Pose2::Zero());
  EXPECT_LT((segment.delta.back() - path.pose.back()).norm(), 1e-6);
  EXPECT_GT((segment.delta.back() - dead_reckon(wheels, params, Pose2::Zero()).pose.back()).norm(),
            1e-3);
  EXPECT_EQ(segment.delta.back().z(), dead_reckon(wheels, params, Pose2::Zero()).pose.back().z());
  // with_tyre_model carries it: the same stream.
  const WheelStream counted = with_tyre_model(wheels, states, model, VehicleBody{});
  ASSERT_EQ(counted.side_slip_rad.size(), wheels.size());
  EXPECT_EQ(counted.side_slip_rad, slipping.side_slip_rad);
  EXPECT_EQ(counted.rev_rl, wheels.rev_rl);
}

TEST(OdometryPreintegration, CovarianceMatchesMonteCarloOfNoisyWheels) {
  // Slip: each increment's arc gets white noise of variance slip^2 |arc|; quantisation: every
  // inner sample's cumulative count is off by sigma q (+e in its increment, -e in the next one).
  const WheelStream wheels = curving_wheels();
  const OdometryParams params{1.95, 1.96, 1.6};
  const WheelNoise noise{0.01, 0.004};
  const PreintegratedSegment model = preintegrate(wheels, 0, 120, params, noise);
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const int runs = 4000;
  std::vector<Eigen::Vector3d> ends;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int r = 0; r < runs; ++r) {
    WheelStream noisy = wheels;
    for (std::size_t k = 1; k < noisy.size(); ++k) {
      noisy.rev_rl[k] += gauss(rng) * noise.slip_sigma_m_per_sqrt_m *
                         std::sqrt(std::abs(wheels.rev_rl[k]) / params.circumference_rl_m);
      noisy.rev_rr[k] += gauss(rng) * noise.slip_sigma_m_per_sqrt_m *
                         std::sqrt(std::abs(wheels.rev_rr[k]) / params.circumference_rr_m);
    }
    for (std::size_t m = 1; m + 1 < noisy.size(); ++m) {
      const double e_rl = gauss(rng) * noise.quantisation_sigma_rev;
      const double e_rr = gauss(rng) * noise.quantisation_sigma_rev;
      noisy.rev_rl[m] += e_rl;
      noisy.rev_rl[m + 1] -= e_rl;
      noisy.rev_rr[m] += e_rr;
      noisy.rev_rr[m + 1] -= e_rr;
    }
    ends.push_back(preintegrate(noisy, 0, 120, params, {}).delta.back());
    mean += ends.back() / runs;
  }
  Eigen::Matrix3d sample = Eigen::Matrix3d::Zero();
  for (const auto& end : ends) sample += (end - mean) * (end - mean).transpose() / (runs - 1);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(sample(i, i), model.covariance(i, i), 0.08 * model.covariance(i, i)) << i;
  }
  EXPECT_NEAR(sample(1, 2) / std::sqrt(sample(1, 1) * sample(2, 2)),
              model.covariance(1, 2) / std::sqrt(model.covariance(1, 1) * model.covariance(2, 2)),
              0.05);
}

}  // namespace
}  // namespace odocal
