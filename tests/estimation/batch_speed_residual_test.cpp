// The batch's Doppler speed residual (closed forms): the integral of the interpolated speed, what
// the fixes must cover, and the wheels' distance against it with the tyre model, the count
// errors, the antenna's lever arm in a turn and the latency. Fast: runs under the sanitizers.

#include "estimation/batch_speed_residual.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace odocal::batch {
namespace {

// Fixes every 0.1 s from 0 to 3 s of a speed 5 + 2 t (linear: its interpolation is exact).
GnssStream accelerating() {
  GnssStream gnss;
  for (int k = 0; k <= 30; ++k) {
    const double t = 0.1 * k;
    gnss.t_s.push_back(t);
    gnss.x_m.push_back(0.0);
    gnss.y_m.push_back(0.0);
    gnss.speed_mps.push_back(5.0 + 2.0 * t);
  }
  return gnss;
}

double integral(const DopplerInterval& interval, const GnssStream& gnss) {
  double sum = 0.0;
  for (std::size_t f = 0; f < interval.fixes.size(); ++f)
    sum += interval.weights_s[f] * gnss.speed_mps[interval.fixes[f]];
  return sum;
}

TEST(DopplerInterval, IntegratesTheInterpolatedSpeedBetweenAnyTwoInstants) {
  const GnssStream gnss = accelerating();
  const auto interval = doppler_interval(gnss, 0.35, 1.27, 0.5, 1.0);
  ASSERT_TRUE(interval.has_value());
  EXPECT_EQ(interval->fixes.front(), 3u);  // 0.3 s, the last at or before the start
  EXPECT_EQ(interval->fixes.back(), 13u);  // 1.3 s, the first at or after the end
  EXPECT_NEAR(integral(*interval, gnss), 5.0 * 0.92 + (1.27 * 1.27 - 0.35 * 0.35), 1e-12);
  EXPECT_NEAR(interval->speed_change_mps, 2.0 * 0.92, 1e-12);
  double weights = 0.0;
  for (const double w : interval->weights_s) weights += w;
  EXPECT_NEAR(weights, 0.92, 1e-12);
  // On the fixes' own instants too.
  const auto exact = doppler_interval(gnss, 1.0, 2.0, 0.5, 1.0);
  ASSERT_TRUE(exact.has_value());
  EXPECT_NEAR(integral(*exact, gnss), 5.0 + (4.0 - 1.0), 1e-12);
  EXPECT_NEAR(exact->sum_squared_weights_s2, 9 * 0.01 + 2 * 0.0025, 1e-12);
}

TEST(DopplerInterval, LeavesOutWhatTheFixesDoNotCover) {
  const GnssStream gnss = accelerating();
  EXPECT_FALSE(doppler_interval(gnss, -0.5, 0.5, 0.5, 1.0));  // before the first fix
  EXPECT_FALSE(doppler_interval(gnss, 2.5, 3.5, 0.5, 1.0));   // past the last
  EXPECT_FALSE(doppler_interval(gnss, 1.0, 2.0, 0.05, 1.0));  // fixes further apart than allowed
  EXPECT_FALSE(doppler_interval(gnss, 1.0, 2.0, 0.5, 7.1));   // slower than the least speed
  GnssStream without = gnss;
  without.speed_mps.clear();
  EXPECT_FALSE(doppler_interval(without, 1.0, 2.0, 0.5, 1.0));
  GnssStream gap = gnss;
  gap.t_s.erase(gap.t_s.begin() + 15, gap.t_s.begin() + 20);
  gap.speed_mps.erase(gap.speed_mps.begin() + 15, gap.speed_mps.begin() + 20);
  EXPECT_FALSE(doppler_interval(gap, 1.0, 2.5, 0.5, 1.0));
  EXPECT_TRUE(doppler_interval(gap, 1.0, 2.5, 0.7, 1.0));
}

double evaluate(const SpeedResidual& residual, const ParamsVector& params,
                const Eigen::Vector2d& lever = Eigen::Vector2d::Zero(), double latency = 0.0,
                const Eigen::Vector2d& count_a = Eigen::Vector2d::Zero(),
                const Eigen::Vector2d& count_b = Eigen::Vector2d::Zero()) {
  double r = 0.0;
  EXPECT_TRUE(residual(params.data(), lever.data(), &latency, count_a.data(), count_b.data(), &r));
  return r;
}

TEST(SpeedResidual, IsZeroWhereTheWheelsRollTheMeasuredDistance) {
  // 10 revolutions per wheel at the tyre model's factors 1 + x . k, the side slip's 1 / cos(beta)
  // to second order, and a count error that adds 0.3 / -0.1 revolution at the end.
  ParamsVector params = ParamsVector::Zero();
  params << 2.0, 2.01, 1.6, 0, 0, 0, 0, 0, 0, 0, 0.002, 0.01, 0.0, -0.005;
  SpeedResidual residual;
  residual.half_revolutions = {5.0, 5.0};
  residual.half_tyre_revolutions(0, 7) = 0.5 * 10.0 * -2.0;  // every increment's x_load = -2
  residual.half_tyre_revolutions(1, 7) = 0.5 * 10.0 * 1.0;
  residual.half_tyre_revolutions(0, 8) = 0.5 * 10.0 * 0.3;
  residual.half_tyre_revolutions(1, 8) = 0.5 * 10.0 * 0.3;
  residual.half_side_slip_revolutions = {0.5 * 10.0 * 0.5 * 16.0, 0.5 * 10.0 * 0.5 * 16.0};
  const double beta = -0.005 * 4.0;  // f_y = 4 m/s^2
  const double left = 2.0 * (10.0 + 0.3) * (1.0 - 2.0 * 0.002 + 0.3 * 0.01);
  const double right = 2.01 * (10.0 - 0.1) * (1.0 + 1.0 * 0.002 + 0.3 * 0.01);
  // (The factors of the count errors' revolutions are left out of the model: a few per mille of
  // a fraction of a revolution.)
  const double distance = 0.5 * (left + right) + 0.5 * (2.0 * 10.0 + 2.01 * 10.0) * beta * beta / 2;
  const double count_share =
      0.5 * (2.0 * 0.3 * (-2.0 * 0.002 + 0.3 * 0.01) + 2.01 * -0.1 * (1.0 * 0.002 + 0.3 * 0.01));
  residual.shares = {{1.0, distance - count_share, 0.0}};
  residual.sigma_m = 0.01;
  EXPECT_NEAR(evaluate(residual, params, Eigen::Vector2d::Zero(), 0.0, Eigen::Vector2d::Zero(),
                       Eigen::Vector2d(0.3, -0.1)),
              0.0, 1e-9);
  // A millimetre more circumference per wheel is ~10 mm more distance: a sigma.
  params(0) += 1e-3;
  params(1) += 1e-3;
  EXPECT_NEAR(evaluate(residual, params, Eigen::Vector2d::Zero(), 0.0, Eigen::Vector2d::Zero(),
                       Eigen::Vector2d(0.3, -0.1)),
              1.0, 0.02);
}

TEST(SpeedResidual, TakesTheAntennaLeverArmOutOfATurn) {
  // The reference point at 10 m/s turning at 0.5 rad/s for 1 s; the antenna 1.5 m ahead and
  // 0.3 m left moves at (10 - w l_y, w l_x) in the body frame.
  const double v = 10.0, w = 0.5;
  const Eigen::Vector2d lever(1.5, 0.3);
  const double antenna = std::hypot(v - w * lever.y(), w * lever.x());
  ParamsVector params = ParamsVector::Zero();
  params(0) = params(1) = 2.0;
  SpeedResidual residual;
  residual.half_revolutions = {2.5, 2.5};  // 10 m
  residual.shares = {{0.5, antenna, w}, {0.5, antenna, w}};
  residual.sigma_m = 0.01;
  EXPECT_NEAR(evaluate(residual, params, lever), 0.0, 1e-9);
  EXPECT_GT(std::abs(evaluate(residual, params)), 10.0);  // without the lever: 0.14 m off
}

TEST(SpeedResidual, TakesTheRearAxlesSideSlipOutOfTheLeverArm) {
  // The reference point at 4 m/s along its course, which lies beta = k_side_slip f_y = -0.005 x 2
  // rad left of the heading, turning at 0.5 rad/s for 1 s (the urban drive's corners); the antenna
  // 2 m ahead and 0.3 m left moves at the reference point's velocity plus w x l, in the body frame.
  const double v = 4.0, w = 0.5, k_side_slip = -0.005, f_y = 2.0, beta = k_side_slip * f_y;
  const Eigen::Vector2d lever(2.0, 0.3);
  const double antenna =
      std::hypot(v * std::cos(beta) - w * lever.y(), v * std::sin(beta) + w * lever.x());
  ParamsVector params = ParamsVector::Zero();
  params(0) = params(1) = 2.0;
  params(3 + kSideSlipCoefficient) = k_side_slip;
  SpeedResidual residual;
  residual.half_revolutions = {1.0, 1.0};  // 4 m of ground; the wheels' 1 / cos(beta) left out
  residual.shares = {{0.5, antenna, w, f_y}, {0.5, antenna, w, f_y}};
  residual.sigma_m = 0.001;
  EXPECT_NEAR(evaluate(residual, params, lever), 0.0, 1e-9);
  // Without the side slip the antenna's across-track speed is short by v beta: 4 mm in 4 m, as a
  // lever arm some 8 cm shorter would leave it.
  ParamsVector without = params;
  without(3 + kSideSlipCoefficient) = 0.0;
  EXPECT_GT(std::abs(evaluate(residual, without, lever)), 3.0);
  EXPECT_NEAR(evaluate(residual, without, Eigen::Vector2d(lever.x() + k_side_slip * v * v, 0.3)),
              0.0, 0.5);
}

TEST(SpeedResidual, TheLatencyShiftsTheIntegralByItsSpeedChange) {
  // A fix stamped t reports the speed at t - 0.1 s: over a second in which the speed rose by
  // 2 m/s the stamped integral is short by 0.2 m.
  ParamsVector params = ParamsVector::Zero();
  params(0) = params(1) = 2.0;
  SpeedResidual residual;
  residual.half_revolutions = {2.5, 2.5};
  residual.shares = {{1.0, 9.8, 0.0}};
  residual.speed_change_mps = 2.0;
  residual.sigma_m = 0.01;
  EXPECT_NEAR(evaluate(residual, params, Eigen::Vector2d::Zero(), 0.1), 0.0, 1e-9);
  EXPECT_NEAR(evaluate(residual, params), 20.0, 1e-9);
}

}  // namespace
}  // namespace odocal::batch
