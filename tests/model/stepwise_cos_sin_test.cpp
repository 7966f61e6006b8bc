#include "odocal/model/stepwise_cos_sin.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace odocal {
namespace {

TEST(SmallAngleCosSin, MatchesLibmWithinTwoUlpOverItsWholeRange) {
  const double two_ulp = 2.0 * std::numeric_limits<double>::epsilon();
  for (int i = -1000; i <= 1000; ++i) {
    const double angle = kSmallAngleRad * i / 1000.0;
    const CosSin value = small_angle_cos_sin(angle);
    EXPECT_NEAR(value.cos, std::cos(angle), two_ulp) << angle;
    EXPECT_NEAR(value.sin, std::sin(angle), two_ulp * std::abs(angle)) << angle;
  }
}

TEST(StepwiseCosSin, FollowsAWanderingAngleWithinAFewUlp) {
  // Small steps (the series), occasional jumps (libm) and a long run (the periodic resync).
  std::mt19937 rng(7);
  std::normal_distribution<double> step(0.0, 0.02);
  StepwiseCosSin tracked;
  double angle = 1.3;
  double worst = 0.0;
  for (int k = 0; k < 100000; ++k) {
    angle += k % 997 == 0 ? 0.5 : step(rng);
    const CosSin value = tracked(angle);
    worst = std::max(
        {worst, std::abs(value.cos - std::cos(angle)), std::abs(value.sin - std::sin(angle))});
  }
  EXPECT_LT(worst, 1e-14);
}

TEST(StepwiseCosSin, FirstValueAndNonFiniteAnglesComeFromLibm) {
  StepwiseCosSin tracked;
  EXPECT_EQ(tracked(0.25).cos, std::cos(0.25));
  EXPECT_EQ(tracked(0.25).sin, std::sin(0.25));
  EXPECT_TRUE(std::isnan(tracked(NAN).cos));
  EXPECT_EQ(tracked(0.3).sin, std::sin(0.3));  // recovers at once after a NaN
}

}  // namespace
}  // namespace odocal
