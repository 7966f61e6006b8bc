// Which candidate judges a plain fit where no tyre model stands: one that is no tyre, fits the
// log decisively better than the plain model (by kDecisiveBic), and has circumferences to compare;
// none where a tyre fits it better.

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "estimation/batch_fit.hpp"

namespace odocal {
namespace {

using batch::decisive_no_tyre;
using batch::kDecisiveBic;

TyreCandidate candidate(const char* model, double bic, bool tyre) {
  TyreCandidate c{model};
  c.bic = bic;
  c.tyre = tyre;
  c.circumference = {1.96, 1.96};
  return c;
}

TEST(DecisiveNoTyre, NeedsAWinByMoreThanTheDecisiveMargin) {
  constexpr double plain = 1000.0;
  EXPECT_FALSE(decisive_no_tyre({candidate("physical", plain - 0.9 * kDecisiveBic, false)}, plain));
  EXPECT_FALSE(decisive_no_tyre({candidate("physical", plain - kDecisiveBic, false)}, plain));
  EXPECT_EQ(decisive_no_tyre({candidate("physical", plain - 1.1 * kDecisiveBic, false)}, plain),
            0u);
}

TEST(DecisiveNoTyre, TakesTheLowestCriterionAmongThoseThatAreNoTyre) {
  constexpr double plain = 1000.0;
  const std::vector<TyreCandidate> candidates{candidate("physical", 950.0, false),
                                              candidate("extended", 900.0, false),
                                              candidate("other", 960.0, false)};
  EXPECT_EQ(decisive_no_tyre(candidates, plain), 1u);
  EXPECT_EQ(decisive_no_tyre({candidates[2], candidates[0]}, plain), 1u);
}

TEST(DecisiveNoTyre, LeavesItToATyreThatFitsTheLogBetter) {
  constexpr double plain = 1000.0;
  const TyreCandidate no_tyre = candidate("physical", 900.0, false);
  EXPECT_FALSE(decisive_no_tyre({no_tyre, candidate("extended", 999.0, true)}, plain));
  EXPECT_EQ(decisive_no_tyre({no_tyre, candidate("extended", 1001.0, true)}, plain), 0u);
}

TEST(DecisiveNoTyre, SkipsAFitWithoutCircumferences) {
  TyreCandidate unusable = candidate("physical", 500.0, false);
  unusable.circumference[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(decisive_no_tyre({unusable}, 1000.0));
  EXPECT_EQ(decisive_no_tyre({unusable, candidate("extended", 900.0, false)}, 1000.0), 1u);
}

}  // namespace
}  // namespace odocal
