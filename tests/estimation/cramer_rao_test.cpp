// The Cramér–Rao bound checked against independent truth: the Fisher information rebuilt from
// numerically differentiated dead reckoning, a straight-line case with a closed-form regression
// variance, and the exact scalings with measurement count and noise.

#include "odocal/estimation/cramer_rao.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>

#include "../support/numerical_jacobian.hpp"
#include "odocal/model/odometry_model.hpp"

namespace odocal {
namespace {

using Theta = Eigen::Matrix<double, 5, 1>;  // x0, y0, yaw0, c_RL, c_RR

constexpr double kTrackWidth = 1.6;

// 20 s at 50 Hz: straight, a left arc, a tighter right arc. GNSS at 5 Hz and headings at 10 Hz,
// stamped between wheel samples so that the interpolation is exercised.
Log winding_log() {
  Log log;
  log.wheels.t_s.push_back(0.0);
  log.wheels.rev_rl.push_back(0.0);
  log.wheels.rev_rr.push_back(0.0);
  for (int k = 1; k <= 1000; ++k) {
    const double turn = k < 300 ? 0.0 : (k < 650 ? 0.004 : -0.007);  // rev difference per step
    log.wheels.t_s.push_back(0.02 * k);
    log.wheels.rev_rl.push_back(0.09 - turn);
    log.wheels.rev_rr.push_back(0.09 + turn);
  }
  for (double t = 0.013; t < 20.0; t += 0.2) log.gnss.t_s.push_back(t);
  log.heading.emplace();
  for (double t = 0.007; t < 20.0; t += 0.1) log.heading->t_s.push_back(t);
  return log;
}

// Dead-reckoned pose at time t_s for the unknowns theta (linear between wheel samples).
Pose2 pose_at(const Log& log, const Theta& theta, double t_s) {
  const OdometryParams params{theta(3), theta(4), kTrackWidth};
  Pose2 pose = theta.head<3>();
  for (std::size_t k = 0; k + 1 < log.wheels.size(); ++k) {
    const Pose2 next = predict_pose(pose, log.wheels.increment(k + 1), params);
    if (t_s < log.wheels.t_s[k + 1]) {
      const double weight = (t_s - log.wheels.t_s[k]) / (log.wheels.t_s[k + 1] - log.wheels.t_s[k]);
      return (1.0 - weight) * pose + weight * next;
    }
    pose = next;
  }
  return pose;
}

TEST(CramerRaoBound, EqualsTheInverseFisherInformationOfNumericalSensitivities) {
  const Log log = winding_log();
  Theta theta;
  theta << 3.0, -2.0, 0.4, 1.9641, 1.9702;
  const CramerRaoOptions options{.gnss_sigma_m = 2.0, .heading_sigma_rad = 0.1};
  const CramerRaoBound bound = circumference_cramer_rao_bound(
      log, {theta(3), theta(4), kTrackWidth}, theta.head<3>(), options);

  Eigen::Matrix<double, 5, 5> fisher = Eigen::Matrix<double, 5, 5>::Zero();
  for (const double t : log.gnss.t_s) {
    const auto S = testing::numerical_jacobian<3, 5>(
        [&](const Theta& x) { return pose_at(log, x, t); }, theta);
    fisher += S.topRows<2>().transpose() * S.topRows<2>() / 4.0;
  }
  for (const double t : log.heading->t_s) {
    const auto S = testing::numerical_jacobian<3, 5>(
        [&](const Theta& x) { return pose_at(log, x, t); }, theta);
    fisher += S.row(2).transpose() * S.row(2) / 0.01;
  }
  const Eigen::Matrix<double, 5, 5> expected =
      fisher.ldlt().solve(Eigen::Matrix<double, 5, 5>::Identity());
  EXPECT_EQ(bound.gnss_used, log.gnss.t_s.size());
  EXPECT_EQ(bound.heading_used, log.heading->t_s.size());
  ASSERT_TRUE(bound.informative());
  for (int r = 0; r < 5; ++r) {
    for (int c = 0; c < 5; ++c) {
      EXPECT_NEAR(bound.covariance(r, c), expected(r, c),
                  1e-5 * std::sqrt(expected(r, r) * expected(c, c)))
          << r << "," << c;
    }
  }
  EXPECT_DOUBLE_EQ(bound.sigma_c_rl_m, std::sqrt(bound.covariance(3, 3)));
}

// Poses at the wheel samples `at` for v = [theta (5), count errors of RL at every sample,
// count errors of RR at every sample]: a cumulative count error e_j adds e_j to increment j and
// takes it from increment j + 1.
Eigen::VectorXd measured_poses(const Log& log, const std::vector<std::size_t>& at,
                               const Eigen::VectorXd& v) {
  const auto n = static_cast<Eigen::Index>(log.wheels.size());
  const OdometryParams params{v(3), v(4), kTrackWidth};
  Eigen::VectorXd out(3 * static_cast<Eigen::Index>(at.size()));
  Pose2 pose = v.head<3>();
  std::size_t next = 0;
  for (std::size_t k = 0; k < log.wheels.size(); ++k) {
    if (k > 0) {
      const auto i = static_cast<Eigen::Index>(k);
      const WheelIncrement increment{log.wheels.rev_rl[k] + v(5 + i) - v(4 + i),
                                     log.wheels.rev_rr[k] + v(5 + n + i) - v(4 + n + i)};
      pose = predict_pose(pose, increment, params);
    }
    if (next < at.size() && at[next] == k)
      out.segment<3>(3 * static_cast<Eigen::Index>(next++)) = pose;
  }
  return out;
}

class CramerRaoCorrelatedNoise : public ::testing::TestWithParam<double> {};

TEST_P(CramerRaoCorrelatedNoise, EqualsTheDenseCorrelatedNoiseInformation) {
  // Independent truth: every measurement's sensitivity to theta and to every count error by
  // central differences, the full noise covariance R + q^2 G G^T (+ the Gauss-Markov GNSS error's
  // sigma^2 exp(-|t_i - t_j| / tau) per axis, white part = total - that), and S^T Sigma^-1 S
  // inverted. Parameter: the Gauss-Markov sigma (0: quantisation only).
  Log log = winding_log();
  log.wheels.t_s.resize(241);
  log.wheels.rev_rl.resize(241);
  log.wheels.rev_rr.resize(241);
  std::vector<std::size_t> at;
  log.gnss.t_s.clear();
  log.heading->t_s.clear();
  for (std::size_t k = 0; k < log.wheels.size(); k += 3) {
    at.push_back(k);
    log.gnss.t_s.push_back(log.wheels.t_s[k]);
    log.heading->t_s.push_back(log.wheels.t_s[k]);
  }
  const double gnss_sigma = 0.05, heading_sigma = 0.02, q = 0.02;
  const double markov_sigma = GetParam(), tau = 1.5;
  Eigen::VectorXd v = Eigen::VectorXd::Zero(5 + 2 * static_cast<Eigen::Index>(log.wheels.size()));
  v.head<5>() << 3.0, -2.0, 0.4, 1.9641, 1.9702;
  const Eigen::MatrixXd J = testing::numerical_jacobian(
      [&](const Eigen::VectorXd& x) { return measured_poses(log, at, x); }, v);
  // Rows: x, y of every fix, then every heading.
  const auto m = static_cast<Eigen::Index>(at.size());
  Eigen::MatrixXd rows(3 * m, J.cols());
  Eigen::VectorXd variance(3 * m);
  for (Eigen::Index j = 0; j < m; ++j) {
    rows.row(2 * j) = J.row(3 * j);
    rows.row(2 * j + 1) = J.row(3 * j + 1);
    rows.row(2 * m + j) = J.row(3 * j + 2);
    variance(2 * j) = variance(2 * j + 1) = gnss_sigma * gnss_sigma;
    variance(2 * m + j) = heading_sigma * heading_sigma;
  }
  const Eigen::MatrixXd S = rows.leftCols<5>();
  const Eigen::MatrixXd G = rows.rightCols(rows.cols() - 5);
  Eigen::MatrixXd sigma = q * q * G * G.transpose();
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < m; ++j) {
      const double dt =
          log.gnss.t_s[static_cast<std::size_t>(i)] - log.gnss.t_s[static_cast<std::size_t>(j)];
      const double markov = markov_sigma * markov_sigma * std::exp(-std::abs(dt) / tau);
      sigma(2 * i, 2 * j) += markov;
      sigma(2 * i + 1, 2 * j + 1) += markov;
    }
    variance(2 * i) -= markov_sigma * markov_sigma;
    variance(2 * i + 1) -= markov_sigma * markov_sigma;
  }
  sigma.diagonal() += variance;
  const Eigen::MatrixXd fisher = S.transpose() * sigma.ldlt().solve(S);
  const Eigen::MatrixXd expected = fisher.ldlt().solve(Eigen::MatrixXd::Identity(5, 5));

  const CramerRaoOptions options{.gnss_sigma_m = gnss_sigma,
                                 .heading_sigma_rad = heading_sigma,
                                 .quantisation_sigma_rev = q,
                                 .gnss_gauss_markov_sigma_m = markov_sigma,
                                 .gnss_gauss_markov_tau_s = tau};
  const OdometryParams params{v(3), v(4), kTrackWidth};
  const CramerRaoBound bound = circumference_cramer_rao_bound(log, params, v.head<3>(), options);
  ASSERT_TRUE(bound.informative());
  for (int r = 0; r < 5; ++r) {
    for (int c = 0; c < 5; ++c) {
      EXPECT_NEAR(bound.covariance(r, c), expected(r, c),
                  1e-4 * std::sqrt(expected(r, r) * expected(c, c)))
          << r << "," << c;
    }
  }
  // The quantisation costs accuracy here: the bound with exact counts is clearly tighter.
  const CramerRaoBound exact = circumference_cramer_rao_bound(
      log, params, v.head<3>(), {.gnss_sigma_m = gnss_sigma, .heading_sigma_rad = heading_sigma});
  EXPECT_LT(exact.sigma_c_rl_m, 0.9 * bound.sigma_c_rl_m);
}

INSTANTIATE_TEST_SUITE_P(QuantisationAndGaussMarkov, CramerRaoCorrelatedNoise,
                         ::testing::Values(0.0, 0.03));

TEST(CramerRaoBound, StraightLineCommonScaleHasTheRegressionVariance) {
  // Driving straight east, x_j = x0 + s n_j to first order with s = (c_RL + c_RR) / 2 and n_j
  // the revolutions up to fix j; y and heading do not depend on x0 or s. So
  // var(s) = sigma^2 / sum (n_j - mean n)^2, the slope variance of a line fit.
  Log log;
  for (int k = 0; k <= 500; ++k) {
    log.wheels.t_s.push_back(0.02 * k);
    log.wheels.rev_rl.push_back(k == 0 ? 0.0 : 0.1);
    log.wheels.rev_rr.push_back(k == 0 ? 0.0 : 0.1);
  }
  std::vector<double> revolutions;
  for (int k = 0; k <= 500; k += 10) {
    log.gnss.t_s.push_back(0.02 * k);
    revolutions.push_back(0.1 * k);
  }
  const double sigma = 1.5;
  const CramerRaoBound bound = circumference_cramer_rao_bound(
      log, {2.0, 2.0, kTrackWidth}, Pose2::Zero(), {.gnss_sigma_m = sigma, .use_heading = false});
  double mean = 0.0;
  for (const double n : revolutions) mean += n / static_cast<double>(revolutions.size());
  double spread = 0.0;
  for (const double n : revolutions) spread += (n - mean) * (n - mean);
  const Eigen::Vector2d half(0.5, 0.5);
  const double var_s = half.dot(bound.covariance.bottomRightCorner<2, 2>() * half);
  EXPECT_NEAR(var_s, sigma * sigma / spread, 1e-9 * sigma * sigma / spread);
}

TEST(CramerRaoBound, ScalesWithMeasurementCountAndNoise) {
  const Log log = winding_log();
  const OdometryParams params{1.96, 1.97, kTrackWidth};
  const CramerRaoOptions gnss_only{.gnss_sigma_m = 3.0, .use_heading = false};
  const CramerRaoBound base = circumference_cramer_rao_bound(log, params, Pose2::Zero(), gnss_only);

  CramerRaoOptions noisier = gnss_only;
  noisier.gnss_sigma_m = 6.0;
  const CramerRaoBound doubled =
      circumference_cramer_rao_bound(log, params, Pose2::Zero(), noisier);
  EXPECT_NEAR(doubled.sigma_c_rl_m / base.sigma_c_rl_m, 2.0, 1e-9);
  EXPECT_NEAR(doubled.sigma_c_rr_m / base.sigma_c_rr_m, 2.0, 1e-9);

  Log twice = log;  // every fix reported twice: twice the information
  twice.gnss.t_s.clear();
  for (const double t : log.gnss.t_s) twice.gnss.t_s.insert(twice.gnss.t_s.end(), {t, t});
  const CramerRaoBound repeated =
      circumference_cramer_rao_bound(twice, params, Pose2::Zero(), gnss_only);
  EXPECT_NEAR(repeated.sigma_c_rl_m / base.sigma_c_rl_m, 1.0 / std::sqrt(2.0), 1e-9);

  // Per-fix sigma from the log overrides the option.
  Log with_sigma = log;
  with_sigma.gnss.sigma_m.assign(log.gnss.t_s.size(), 6.0);
  EXPECT_NEAR(
      circumference_cramer_rao_bound(with_sigma, params, Pose2::Zero(), gnss_only).sigma_c_rl_m,
      doubled.sigma_c_rl_m, 1e-12);

  // Headings only add information.
  const CramerRaoBound with_heading = circumference_cramer_rao_bound(log, params, Pose2::Zero());
  EXPECT_LT(with_heading.sigma_c_rl_m, base.sigma_c_rl_m);
}

TEST(CramerRaoBound, ReportsALogWithoutInformation) {
  Log log = winding_log();
  log.gnss.t_s = {100.0, 101.0};  // after the drive
  log.heading.reset();
  const CramerRaoBound bound =
      circumference_cramer_rao_bound(log, {1.96, 1.97, kTrackWidth}, Pose2::Zero());
  EXPECT_EQ(bound.gnss_used, 0u);
  EXPECT_FALSE(bound.informative());
  EXPECT_TRUE(std::isinf(bound.sigma_c_rl_m));
}

}  // namespace
}  // namespace odocal
