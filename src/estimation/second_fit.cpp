#include "second_fit.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace odocal::batch {

std::array<double, 2> circumferences(const BatchSummary& summary) {
  return {summary.estimate.circumference_rl_m, summary.estimate.circumference_rr_m};
}

bool second_fit_stood(const BatchSummary& with) {
  return with.termination == Termination::kConverged ||
         with.termination == Termination::kNotIdentifiable;
}

const EstimatedParameter* estimated_parameter(const BatchSummary& summary, std::string_view name) {
  const auto p = std::find_if(summary.parameters.begin(), summary.parameters.end(),
                              [&](const EstimatedParameter& q) { return q.name == name; });
  if (p == summary.parameters.end() || !p->estimated || !std::isfinite(p->value) ||
      !std::isfinite(p->sigma) || !(p->sigma > 0.0))
    return nullptr;
  return &*p;
}

BatchSummary keep_one_fit(BatchSummary without, BatchSummary with, bool take_with) {
  BatchSummary& kept = take_with ? with : without;
  const BatchSummary& other = take_with ? without : with;
  kept.tyre_selection.other_solves += other.solves + other.tyre_selection.other_solves;
  return std::move(kept);
}

}  // namespace odocal::batch
