#include "odocal/estimation/median.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace odocal {
namespace {

TEST(Median, MiddleValueUpperForAnEvenCountAndNanForNone) {
  EXPECT_DOUBLE_EQ(median(std::vector<double>{3.0, 1.0, 2.0}), 2.0);
  EXPECT_DOUBLE_EQ(median(std::vector<double>{4.0, 1.0, 3.0, 2.0}), 3.0);
  EXPECT_DOUBLE_EQ(median(std::vector<float>{2.5F, -1.0F}), 2.5);
  EXPECT_TRUE(std::isnan(median(std::vector<double>{})));
}

TEST(Median, NormalSigmaFromAbsoluteValues) {
  EXPECT_DOUBLE_EQ(normal_sigma_from_absolute(std::vector<double>{}), 0.0);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> normal(0.0, 0.3);
  std::vector<double> clean, spoilt;
  std::vector<float> spoilt_float;
  for (int k = 0; k < 100000; ++k) {
    const double x = std::abs(normal(rng));
    clean.push_back(x);
    // One sample in twenty a gross outlier, which a standard deviation would follow.
    const double y = k % 20 == 0 ? 1e3 : x;
    spoilt.push_back(y);
    spoilt_float.push_back(static_cast<float>(y));
  }
  EXPECT_NEAR(normal_sigma_from_absolute(clean), 0.3, 0.005);
  // With a share e of outliers the median m of |x| solves (1 - e)(2 Phi(m / sigma) - 1) = 1 / 2:
  // at e = 0.05, m = 0.7164 sigma, so the estimate is 1.4826 * 0.7164 * 0.3 = 0.3186.
  EXPECT_NEAR(normal_sigma_from_absolute(spoilt), 0.3186, 0.005);
  EXPECT_NEAR(normal_sigma_from_absolute(spoilt_float), normal_sigma_from_absolute(spoilt), 1e-6);
}

}  // namespace
}  // namespace odocal
