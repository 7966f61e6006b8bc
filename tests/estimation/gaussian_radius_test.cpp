// The length of a 2-D Gaussian error against closed forms: a circular one's radius is Rayleigh
// (P(r) = 1 - exp(-r^2 / 2 sigma^2)), a degenerate one's is a half-normal.

#include "estimation/gaussian_radius.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "odocal/error.hpp"

namespace odocal {
namespace {

TEST(GaussianRadius, ACircularErrorIsRayleigh) {
  const Eigen::Matrix2d covariance = 4.0 * Eigen::Matrix2d::Identity();  // sigma 2 m per axis
  for (const double r : {0.5, 2.0, 3.0, 6.0})
    EXPECT_NEAR(gaussian_radius_probability(covariance, r), 1.0 - std::exp(-r * r / 8.0), 1e-9);
  EXPECT_NEAR(gaussian_radius_median({covariance}, {1.0}), 2.0 * std::sqrt(2.0 * std::log(2.0)),
              1e-6);
}

TEST(GaussianRadius, AnErrorAlongOneDirectionIsHalfNormal) {
  // Rotated by 30 degrees: only the length of the error counts, not its direction.
  const Eigen::Vector2d along(std::cos(0.5236), std::sin(0.5236));
  const Eigen::Matrix2d covariance = 9.0 * along * along.transpose();  // sigma 3 m
  EXPECT_NEAR(gaussian_radius_probability(covariance, 3.0), std::erf(1.0 / std::sqrt(2.0)), 1e-3);
  EXPECT_NEAR(gaussian_radius_median({covariance}, {1.0}), 3.0 * 0.6744898, 3e-3);
  // Divided by a scale of 100: the same median, a hundredth of it.
  EXPECT_NEAR(gaussian_radius_median({covariance}, {100.0}), 0.03 * 0.6744898, 3e-5);
}

TEST(GaussianRadius, TheMedianOfASetWeighsItsMembersAlike) {
  // Two circular errors, sigma 1 and 3 m: half of the pooled lengths lie below the median.
  const std::vector<Eigen::Matrix2d> covariances{Eigen::Matrix2d::Identity(),
                                                 9.0 * Eigen::Matrix2d::Identity()};
  const double median = gaussian_radius_median(covariances, {1.0, 1.0});
  const double pooled = 0.5 * (1.0 - std::exp(-median * median / 2.0)) +
                        0.5 * (1.0 - std::exp(-median * median / 18.0));
  EXPECT_NEAR(pooled, 0.5, 1e-9);
  EXPECT_GT(median, 1.0 * std::sqrt(2.0 * std::log(2.0)));
  EXPECT_LT(median, 3.0 * std::sqrt(2.0 * std::log(2.0)));
  EXPECT_EQ(gaussian_radius_median({Eigen::Matrix2d::Zero()}, {1.0}), 0.0);
}

TEST(GaussianRadius, RefusesSetsThatDoNotMatch) {
  EXPECT_THROW(gaussian_radius_median({}, {}), Error);
  EXPECT_THROW(gaussian_radius_median({Eigen::Matrix2d::Identity()}, {1.0, 2.0}), Error);
  EXPECT_THROW(gaussian_radius_median({Eigen::Matrix2d::Identity()}, {0.0}), Error);
}

}  // namespace
}  // namespace odocal
