// Which candidate judges a plain fit where no tyre model stands: one that cannot stand (no tyre,
// or every coefficient held), fits the log decisively better than the plain model (by
// kDecisiveBic), and has circumferences to compare; none where a tyre that can stand fits it
// better. And where none does: a tyre within that margin above the plain model's criterion, whose
// gap the plain fit carries as far as the criteria weigh it.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "estimation/batch_fit.hpp"

namespace odocal {
namespace {

using batch::decisive_fit_that_cannot_stand;
using batch::kDecisiveBic;
using batch::tie_gap_share;
using batch::tyre_fit_not_rejected;

TyreCandidate candidate(const char* model, double bic, bool tyre) {
  TyreCandidate c{model};
  c.bic = bic;
  c.tyre = tyre;
  c.circumference = {1.96, 1.96};
  return c;
}

TEST(DecisiveFitThatCannotStand, NeedsAWinByMoreThanTheDecisiveMargin) {
  constexpr double plain = 1000.0;
  EXPECT_FALSE(decisive_fit_that_cannot_stand(
      {candidate("physical", plain - 0.9 * kDecisiveBic, false)}, plain));
  EXPECT_FALSE(
      decisive_fit_that_cannot_stand({candidate("physical", plain - kDecisiveBic, false)}, plain));
  EXPECT_EQ(decisive_fit_that_cannot_stand(
                {candidate("physical", plain - 1.1 * kDecisiveBic, false)}, plain),
            0u);
}

TEST(DecisiveFitThatCannotStand, TakesTheLowestCriterionAmongThoseThatAreNoTyre) {
  constexpr double plain = 1000.0;
  const std::vector<TyreCandidate> candidates{candidate("physical", 950.0, false),
                                              candidate("extended", 900.0, false),
                                              candidate("other", 960.0, false)};
  EXPECT_EQ(decisive_fit_that_cannot_stand(candidates, plain), 1u);
  EXPECT_EQ(decisive_fit_that_cannot_stand({candidates[2], candidates[0]}, plain), 1u);
}

TEST(DecisiveFitThatCannotStand, LeavesItToATyreThatFitsTheLogBetter) {
  constexpr double plain = 1000.0;
  const TyreCandidate no_tyre = candidate("physical", 900.0, false);
  EXPECT_FALSE(
      decisive_fit_that_cannot_stand({no_tyre, candidate("extended", 999.0, true)}, plain));
  EXPECT_EQ(decisive_fit_that_cannot_stand({no_tyre, candidate("extended", 1001.0, true)}, plain),
            0u);
}

TEST(DecisiveFitThatCannotStand, SkipsAFitWithoutCircumferences) {
  TyreCandidate unusable = candidate("physical", 500.0, false);
  unusable.circumference[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(decisive_fit_that_cannot_stand({unusable}, 1000.0));
  EXPECT_EQ(decisive_fit_that_cannot_stand({unusable, candidate("extended", 900.0, false)}, 1000.0),
            1u);
}

TEST(DecisiveFitThatCannotStand, TakesATyreWhoseEveryCoefficientIsHeld) {
  // The log identified none of its terms: it cannot stand, but fitting the log decisively better
  // with a car's values, it says where the circumferences at rest lie.
  constexpr double plain = 1000.0;
  TyreCandidate held = candidate("physical", 950.0, true);
  held.every_coefficient_held = true;
  EXPECT_EQ(decisive_fit_that_cannot_stand({held}, plain), 0u);
  held.bic = plain - 0.9 * kDecisiveBic;
  EXPECT_FALSE(decisive_fit_that_cannot_stand({held}, plain));
  // Nor does it keep a tyre that can stand and fits the log better from judging.
  held.bic = 950.0;
  EXPECT_FALSE(decisive_fit_that_cannot_stand({held, candidate("extended", 990.0, true)}, plain));
  EXPECT_EQ(decisive_fit_that_cannot_stand({held, candidate("extended", 1010.0, true)}, plain), 0u);
}

// Where neither stands nor fits decisively better: a tyre the log does not decisively reject,
// within kDecisiveBic above the plain model's criterion, the lowest criterion first.
TEST(TyreFitNotRejected, TakesATyreWithinTheDecisiveMarginAboveThePlainModel) {
  constexpr double plain = 1000.0;
  EXPECT_EQ(tyre_fit_not_rejected({candidate("physical", plain + 0.9 * kDecisiveBic, true)}, plain),
            0u);
  EXPECT_FALSE(tyre_fit_not_rejected({candidate("physical", plain + kDecisiveBic, true)}, plain));
  EXPECT_FALSE(tyre_fit_not_rejected({candidate("physical", plain + 5.0, false)}, plain));
  TyreCandidate held = candidate("physical", plain + 5.0, true);
  held.every_coefficient_held = true;
  EXPECT_FALSE(tyre_fit_not_rejected({held}, plain));
  TyreCandidate unfitted = candidate("physical", plain + 5.0, true);
  unfitted.circumference[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(tyre_fit_not_rejected({unfitted}, plain));
  EXPECT_EQ(tyre_fit_not_rejected({candidate("physical", plain + 6.0, true),
                                   candidate("extended", plain + 2.0, true)},
                                  plain),
            1u);
}

// The two models weighed by their criteria as log evidence, e^(-BIC / 2): the rival's weight is
// 1 / (1 + e^(excess / 2)), and the mixture's spread sqrt(w (1 - w)) times the gap.
TEST(TyreFitNotRejected, CarriesTheShareOfTheGapThatTheCriteriaWeigh) {
  EXPECT_DOUBLE_EQ(tie_gap_share(0.0), 0.5);     // equal criteria: half the gap
  const double w = 1.0 / (1.0 + std::exp(5.0));  // 10 above: the weight 0.0067
  EXPECT_NEAR(tie_gap_share(10.0), std::sqrt(w * (1.0 - w)), 1e-15);
  EXPECT_NEAR(tie_gap_share(10.0), 0.0815, 1e-4);
  EXPECT_GT(tie_gap_share(1.5), tie_gap_share(7.5));
  EXPECT_EQ(tie_gap_share(-0.1), 1.0);  // the rival fits better: all of it
}

}  // namespace
}  // namespace odocal
