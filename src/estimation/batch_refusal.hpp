#pragma once
// Why a batch result is refused, in the one line that the command line's error, the JSON's
// message and a fleet's database carry: the circumferences' sigma against the limit and the
// reason once, since both wheels nearly always share it. Every parameter's verdict stays in the
// identifiability line and the JSON's parameters.

#include <string>
#include <vector>

#include "odocal/estimation/batch_calibration.hpp"

namespace odocal {

// Said first, in the identifiability line and the refusal, when no covariance exists.
inline constexpr const char* kRankDeficientReason =
    "the problem is rank-deficient: some unknowns cannot be told apart";

// parameters: the batch's, the two circumferences first. max_sigma_circumference_m: the limit
// their 1-sigma was held to. rank_deficient: no covariance could be computed at all.
// Returns "" when both circumferences are identified and the problem is not rank-deficient.
std::string circumference_refusal(const std::vector<EstimatedParameter>& parameters,
                                  double max_sigma_circumference_m, bool rank_deficient);

}  // namespace odocal
