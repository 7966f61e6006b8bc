// The physical terms' circumferences at rest witnessed by the regression terms, which need no
// body (batch_fit.hpp, witness_physical_fit; docs/tyre-model.md, "A body that vehicle.yaml gets
// wrong"), and the regression terms chosen by hand judged by the physical ones (physical_rival).

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "batch_fit.hpp"

namespace odocal::batch {

bool witness_physical_fit(const CalibrationRun& run, const BatchOptions& fitting,
                          const CalibrationOptions& common, const BatchSummary& unfitted,
                          BatchSummary& summary, int& solves) {
  // It guards an answer that stands: one already refused (its circumferences not identified)
  // is no confident answer, and there the regression terms extrapolate to rest no better (the
  // 2-hour urban drive without a Doppler column, body right: the physical fit -0.3 mm at sigma
  // 1.1 mm, refused; the regression terms -18.7 mm at 3.0 mm, their speed term taking the
  // circumference's place). Fitted there, the witness blamed a right body and cost the 10-hour
  // drive two fits more.
  if (summary.termination != Termination::kConverged) return false;
  BatchSummary witness = unfitted;
  // Where the gap lies inside kWitnessSigmas even of the least combined sigma the witness can
  // report, it cannot fire: its considered uncertainty is not worked out (a tenth of its time on
  // the 10-hour drive). The margin covers the solve that the summary is taken after.
  constexpr double kMargin = 1e-3;
  const auto could_fire = [&](const AdaptedFacts& adapted) {
    if (!adapted.min_variance) return true;  // no floor: see it through
    if (summary.parameters.size() < 2) return false;
    for (std::size_t wheel = 0; wheel < 2; ++wheel) {
      const double gap = adapted.circumference[wheel] - summary.parameters[wheel].value;
      const double floor = std::hypot(summary.parameters[wheel].sigma,
                                      std::sqrt(std::max((*adapted.min_variance)[wheel], 0.0)));
      if (!(std::abs(gap) <= (1.0 - kMargin) * kWitnessSigmas * floor)) return true;
    }
    return false;
  };
  // The mounting is the vehicle's and the latency the log's clocks', not the body's: where the
  // physical fit estimated them, the witness judges the body with them held where that fit put
  // them. A latency free beside the regression terms trades with their longitudinal term (the
  // lag leaves -latency a_x in the along-track residual): the urban drive with the fixes 141 ms
  // late put their circumferences at rest 5.8 mm from the physical terms', 3.2 combined sigma.
  BatchOptions witnessing = fitting;
  for (const EstimatedParameter& p : summary.parameters) {
    if (!p.estimated) continue;
    if (p.name == "lever_arm_x_m") witnessing.lever_arm_x_m = p.value;
    if (p.name == "lever_arm_y_m") witnessing.lever_arm_y_m = p.value;
    if (p.name == "latency_s") witnessing.latency_s = p.value;
  }
  witnessing.estimate_lever_arm = witnessing.estimate_latency = false;
  const bool tyre = fit_model(run, witnessing, common, TyreTerms::kRegression, witness,
                              {.finish =
                                   [&](const FitFacts& facts) {
                                     return facts.usable && is_tyre(facts, unfitted.nominal,
                                                                    common.max_relative_change);
                                   },
                               .go_on = could_fire});
  solves += witness.solves;
  // A witness that is no tyre, or whose circumferences the log leaves open, says nothing.
  if (!tyre || witness.parameters.size() < 2 || summary.parameters.size() < 2) return false;
  std::array<double, 2> at_rest{}, gap_m{};
  double sigmas = 0.0;
  for (std::size_t wheel = 0; wheel < 2; ++wheel) {
    const EstimatedParameter& own = summary.parameters[wheel];
    const EstimatedParameter& other = witness.parameters[wheel];
    at_rest[wheel] = other.value;
    gap_m[wheel] = other.value - own.value;
    const double combined = std::hypot(own.sigma, other.sigma);
    if (!std::isfinite(gap_m[wheel]) || !(combined > 0.0)) return false;
    sigmas = std::max(sigmas, std::abs(gap_m[wheel]) / combined);
  }
  if (!(sigmas > kWitnessSigmas)) return false;
  BatchSummary judged = unfitted;
  // Set first: the circumferences' verdicts name whose gap they carry.
  judged.tyre_selection = summary.tyre_selection;
  judged.tyre_selection.chosen_gap_to = tyre_model_option(TyreTerms::kRegression);
  judged.tyre_selection.chosen_gap_sigmas = sigmas;
  fit_model(run, fitting, common, TyreTerms::kPhysical, judged, {.rival_circumference = at_rest});
  solves += judged.solves;
  std::string& verdict = judged.model_adequacy.verdict;
  verdict += fmt::format(
      "{}tyre_model: {} (its terms need no body) puts the circumferences at rest {:.3g} / "
      "{:.3g} mm from the physical terms' ({:.1f} of their combined sigma), which their sigma "
      "carries: check vehicle.yaml's body (the physical terms rest on it)",
      verdict.empty() ? "" : "; but ", tyre_model_option(TyreTerms::kRegression),
      1e3 * std::abs(gap_m[0]), 1e3 * std::abs(gap_m[1]), sigmas);
  summary = std::move(judged);
  return true;
}

std::optional<std::array<double, 2>> physical_rival(const CalibrationRun& run,
                                                    const BatchOptions& options,
                                                    const CalibrationOptions& common,
                                                    const BatchSummary& unfitted, int& solves) {
  BatchOptions physical = options;
  physical.tyre_model = TyreModelChoice::kPhysical;  // with the Doppler speed it fits by default
  const FitFacts facts =
      solved_facts(run, physical, common, unfitted, TyreTerms::kPhysical, std::nullopt, solves);
  if (!facts.usable) return std::nullopt;
  return facts.circumference;
}

}  // namespace odocal::batch
