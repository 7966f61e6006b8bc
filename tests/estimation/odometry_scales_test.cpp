// The odometry scales of a calibration: closed-form values, and their sigma against a Monte
// Carlo propagation of the parameter covariance.

#include "odocal/estimation/odometry_scales.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <random>

namespace odocal {
namespace {

TEST(OdometryScales, ClosedForm) {
  const OdometryParams nominal{1.0, 1.0, 0.5};
  const OdometryScales scales =
      odometry_scales(nominal, {0.98, 1.00, 0.6}, Eigen::Matrix3d::Zero());
  EXPECT_DOUBLE_EQ(scales.speed_scale, 0.99);
  EXPECT_DOUBLE_EQ(scales.yaw_rate_scale, 0.99 * 0.5 / 0.6);
  EXPECT_EQ(scales.sigma_speed_scale, 0.0);
  EXPECT_EQ(scales.sigma_yaw_rate_scale, 0.0);
}

TEST(OdometryScales, SigmaMatchesMonteCarlo) {
  const OdometryParams nominal{1.04, 1.04, 0.555};
  const OdometryParams calibrated{0.99, 0.995, 0.49};
  Eigen::Matrix3d covariance;
  covariance << 3.0e-4, 2.9e-4, 1.5e-4,  //
      2.9e-4, 3.0e-4, 1.5e-4,            //
      1.5e-4, 1.5e-4, 1.2e-4;
  const OdometryScales scales = odometry_scales(nominal, calibrated, covariance);
  const Eigen::Matrix3d L = covariance.llt().matrixL();
  std::mt19937_64 rng(7);
  std::normal_distribution<double> unit;
  double sum_v = 0, sum_vv = 0, sum_w = 0, sum_ww = 0;
  constexpr int kSamples = 200'000;
  for (int i = 0; i < kSamples; ++i) {
    const Eigen::Vector3d d = L * Eigen::Vector3d(unit(rng), unit(rng), unit(rng));
    const double v = (calibrated.circumference_rl_m + d(0) + calibrated.circumference_rr_m + d(1)) /
                     (nominal.circumference_rl_m + nominal.circumference_rr_m);
    const double w = v * nominal.track_width_m / (calibrated.track_width_m + d(2));
    sum_v += v;
    sum_vv += v * v;
    sum_w += w;
    sum_ww += w * w;
  }
  const auto sd = [](double sum, double sum_sq) {
    return std::sqrt(sum_sq / kSamples - (sum / kSamples) * (sum / kSamples));
  };
  EXPECT_NEAR(scales.sigma_speed_scale, sd(sum_v, sum_vv), 0.02 * scales.sigma_speed_scale);
  // First order: within a few per cent of the sampled spread at this 2 % track sigma.
  EXPECT_NEAR(scales.sigma_yaw_rate_scale, sd(sum_w, sum_ww), 0.05 * scales.sigma_yaw_rate_scale);
}

}  // namespace
}  // namespace odocal
