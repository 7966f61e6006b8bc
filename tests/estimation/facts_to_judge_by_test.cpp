// Which fit a tyre model is judged by: its own (under the configured GNSS noise), or, where that
// one wandered, its fit under the noise the plain fit's residuals showed, if that one can stand.

#include <gtest/gtest.h>

#include <optional>

#include "estimation/batch_fit.hpp"

namespace odocal {
namespace {

using batch::facts_to_judge_by;
using batch::FitFacts;

constexpr double kMaxChange = 0.05;

OdometryParams nominal() {
  OdometryParams p;
  p.circumference_rl_m = p.circumference_rr_m = 1.96;
  return p;
}

// A fit that can stand: usable, a coefficient free, a tyre's effect, circumferences in the band.
FitFacts standing_fit() {
  FitFacts f;
  f.usable = true;
  f.free_tyre_coefficients = 3;
  f.max_tyre_effect = 0.002;
  f.circumference = {1.97, 1.97};
  return f;
}

FitFacts wandered_fit() {
  FitFacts f = standing_fit();
  f.free_tyre_coefficients = 0;
  f.wandered = true;
  f.circumference = {1.95, 1.95};
  return f;
}

TEST(FactsToJudgeBy, AFitThatWanderedIsJudgedByItsFitUnderTheNoiseShown) {
  const FitFacts own = wandered_fit();
  const std::optional<FitFacts> shared = standing_fit();
  EXPECT_EQ(&facts_to_judge_by(own, shared, nominal(), kMaxChange), &*shared);
}

TEST(FactsToJudgeBy, AFitThatSettledStandsAsItIs) {
  const std::optional<FitFacts> shared = standing_fit();
  FitFacts held = wandered_fit();  // every coefficient held as unidentified
  held.wandered = false;
  EXPECT_EQ(&facts_to_judge_by(held, shared, nominal(), kMaxChange), &held);
  FitFacts no_tyre = standing_fit();  // coefficients of percents
  no_tyre.max_tyre_effect = 0.2;
  EXPECT_EQ(&facts_to_judge_by(no_tyre, shared, nominal(), kMaxChange), &no_tyre);
  const FitFacts own = standing_fit();
  EXPECT_EQ(&facts_to_judge_by(own, shared, nominal(), kMaxChange), &own);
}

TEST(FactsToJudgeBy, TheNoiseShownSpeaksOnlyWhereItsFitCanStand) {
  const FitFacts own = wandered_fit();
  EXPECT_EQ(&facts_to_judge_by(own, std::nullopt, nominal(), kMaxChange), &own);
  std::optional<FitFacts> shared = standing_fit();
  shared->max_tyre_effect = 0.2;  // no tyre
  EXPECT_EQ(&facts_to_judge_by(own, shared, nominal(), kMaxChange), &own);
  shared = standing_fit();
  shared->circumference = {2.2, 2.2};  // out of the band
  EXPECT_EQ(&facts_to_judge_by(own, shared, nominal(), kMaxChange), &own);
  shared = wandered_fit();  // wandered there too
  EXPECT_EQ(&facts_to_judge_by(own, shared, nominal(), kMaxChange), &own);
  shared = standing_fit();
  shared->usable = false;
  EXPECT_EQ(&facts_to_judge_by(own, shared, nominal(), kMaxChange), &own);
  FitFacts unusable = own;
  unusable.usable = false;
  EXPECT_EQ(&facts_to_judge_by(unusable, standing_fit(), nominal(), kMaxChange), &unusable);
}

}  // namespace
}  // namespace odocal
