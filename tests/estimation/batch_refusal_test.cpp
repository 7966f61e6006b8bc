// The one line that says why a batch result is refused: the circumferences' sigma against the
// limit, each wheel's reason once, and nothing of the parameters that do not refuse it.

#include "estimation/batch_refusal.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

namespace odocal {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::vector<EstimatedParameter> parameters(const std::string& rl_verdict, double rl_sigma_m,
                                           const std::string& rr_verdict, double rr_sigma_m) {
  return {
      {"circumference_rl_m", 1.96, rl_sigma_m, true, rl_verdict.empty(), rl_verdict},
      {"circumference_rr_m", 1.96, rr_sigma_m, true, rr_verdict.empty(), rr_verdict},
      {"tyre_drive_slip", 0.05, 0.01, true, false, "the drive has too little of what shows it"}};
}

TEST(BatchRefusal, IdentifiedCircumferencesRefuseNothing) {
  EXPECT_EQ(circumference_refusal(parameters("", 3e-4, "", 3e-4), 1e-3, false), "");
}

TEST(BatchRefusal, AReasonBothWheelsShareIsSaidOnceWithEachSigma) {
  const std::string text = circumference_refusal(
      parameters("an extrapolation (1.2 mm of the sigma from the body, 0.77 mm of it)", 3.12e-3,
                 "an extrapolation (1.2 mm of the sigma from the body, 0.78 mm of it)", 3.13e-3),
      1e-3, false);
  EXPECT_EQ(text,
            "not identified: circumference_rl_m 1-sigma 3.12 mm, circumference_rr_m 1-sigma "
            "3.13 mm (max_sigma_circumference_m 1 mm): an extrapolation (1.2 mm of the sigma "
            "from the body, 0.77 mm of it)");
  EXPECT_THAT(text, Not(HasSubstr("tyre_drive_slip")));  // held or loose, it refuses nothing
}

TEST(BatchRefusal, DifferentReasonsAreEachSaid) {
  const std::string text = circumference_refusal(
      parameters("too few turns", 2e-3, "a gap in its encoder", 5e-3), 1e-3, false);
  EXPECT_THAT(text, HasSubstr("(max_sigma_circumference_m 1 mm): too few turns; "
                              "circumference_rr_m: a gap in its encoder"));
}

TEST(BatchRefusal, OneWheelAloneIsNamedAlone) {
  const std::string text =
      circumference_refusal(parameters("", 4e-4, "too few turns", 2e-3), 1e-3, false);
  EXPECT_EQ(text,
            "not identified: circumference_rr_m 1-sigma 2 mm (max_sigma_circumference_m 1 mm): "
            "too few turns");
}

TEST(BatchRefusal, ARankDeficientProblemSaysSoFirst) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::string text = circumference_refusal(
      parameters("cannot be told apart", inf, "cannot be told apart", inf), 1e-3, true);
  EXPECT_THAT(text, HasSubstr("not identified: the problem is rank-deficient"));
  EXPECT_THAT(text, HasSubstr("circumference_rl_m 1-sigma not computable"));
}

}  // namespace
}  // namespace odocal
