#include "odocal/estimation/paired_moments.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace odocal {
namespace {

TEST(PairedMoments, AnExactLineHasItsSlopeAndCorrelationOne) {
  PairedMoments rising, falling;
  for (int k = 0; k < 10; ++k) {
    rising.add(k, 2.0 * k + 1.0);
    falling.add(k, 5.0 - 0.5 * k);
  }
  EXPECT_EQ(rising.count(), 10U);
  EXPECT_NEAR(rising.slope(), 2.0, 1e-12);
  EXPECT_NEAR(rising.correlation(), 1.0, 1e-12);
  EXPECT_NEAR(falling.slope(), -0.5, 1e-12);
  EXPECT_NEAR(falling.correlation(), -1.0, 1e-12);
  // 0..9: variance (n^2 - 1) / 12 about the mean.
  EXPECT_NEAR(rising.variance_x(), 99.0 / 12.0, 1e-12);
  EXPECT_NEAR(rising.variance_y(), 4.0 * 99.0 / 12.0, 1e-12);
}

TEST(PairedMoments, NoiseLowersTheCorrelationToItsExpectedValue) {
  // y = x + n with var(x) = var(n): correlation 1 / sqrt(2), slope 1.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  PairedMoments moments;
  for (int k = 0; k < 200000; ++k) {
    const double x = normal(rng);
    moments.add(x, x + normal(rng));
  }
  EXPECT_NEAR(moments.correlation(), 1.0 / std::sqrt(2.0), 0.01);
  EXPECT_NEAR(moments.slope(), 1.0, 0.01);
}

TEST(PairedMoments, WhatDoesNotVaryHasNoSlopeOrCorrelation) {
  PairedMoments none, flat_x, flat_y;
  EXPECT_TRUE(std::isnan(none.slope()));
  EXPECT_TRUE(std::isnan(none.correlation()));
  for (int k = 0; k < 5; ++k) {
    flat_x.add(1.0, k);
    flat_y.add(k, 1.0);
  }
  EXPECT_TRUE(std::isnan(flat_x.slope()));
  EXPECT_TRUE(std::isnan(flat_x.correlation()));
  EXPECT_NEAR(flat_y.slope(), 0.0, 1e-15);
  EXPECT_TRUE(std::isnan(flat_y.correlation()));
}

}  // namespace
}  // namespace odocal
