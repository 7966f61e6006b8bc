// The split-sample check: each part of the log fitted alone, with the whole log's tyre model and
// without the refusal, the model judgement and the dead-reckoning judgement (its sigma is the
// data's, which is what is compared).
#include "batch_consistency.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "odocal/error.hpp"
#include "odocal/estimation/log_window.hpp"

namespace odocal::batch {
namespace {

// The tyre model the whole log's fit stands on, for its parts: auto's choice, or the one asked.
TyreModelChoice whole_log_model(const BatchOptions& options, const BatchSummary& summary) {
  if (options.tyre_model != TyreModelChoice::kAuto) return options.tyre_model;
  if (summary.tyre_selection.chosen == "physical") return TyreModelChoice::kPhysical;
  if (summary.tyre_selection.chosen == "extended") return TyreModelChoice::kExtended;
  return TyreModelChoice::kNone;
}

bool part_result_fits(const BatchSummary& part) {
  if (part.termination != Termination::kConverged &&
      part.termination != Termination::kNotIdentifiable)
    return false;
  const double sigmas[] = {part.sigma_rl_m(), part.sigma_rr_m()};
  return std::isfinite(part.estimate.circumference_rl_m) &&
         std::isfinite(part.estimate.circumference_rr_m) &&
         std::all_of(std::begin(sigmas), std::end(sigmas),
                     [](double s) { return std::isfinite(s) && s > 0.0; });
}

PartsConsistency::Part fit_part(const Log& log, double from_s, double to_s,
                                const BatchOptions& options, const CalibrationOptions& common) {
  PartsConsistency::Part part{from_s, to_s};
  try {
    const BatchSummary result = calibrate_batch(crop_log(log, from_s, to_s), options, common);
    if (!part_result_fits(result)) return part;
    part.fitted = true;
    part.circumference_m = {result.estimate.circumference_rl_m, result.estimate.circumference_rr_m};
    part.sigma_m = {result.sigma_rl_m(), result.sigma_rr_m()};
  } catch (const Error&) {
    // A part too short or without motion to calibrate: left out, as the count says.
  }
  return part;
}

void widen_sigma(const std::array<double, 2>& scale, BatchSummary& summary) {
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) {
      const double s = scale[static_cast<std::size_t>(i)] * scale[static_cast<std::size_t>(j)];
      summary.covariance(i, j) *= s;
      summary.params_covariance(i, j) *= s;
    }
    summary.parameters[static_cast<std::size_t>(i)].sigma *= scale[static_cast<std::size_t>(i)];
  }
  if (summary.reference_circumference) {
    summary.reference_circumference->sigma_rl_m *= scale[0];
    summary.reference_circumference->sigma_rr_m *= scale[1];
  }
}

}  // namespace

double birge_ratio_bound(int dof) {
  constexpr double kZ95 = 1.6448536269514722;  // the standard normal's 95 % quantile
  const double k = static_cast<double>(dof);
  const double cube_root = 1.0 - 2.0 / (9.0 * k) + kZ95 * std::sqrt(2.0 / (9.0 * k));
  return std::sqrt(cube_root * cube_root * cube_root);
}

void check_parts_consistency(const Log& log, const BatchOptions& options,
                             const CalibrationOptions& common, BatchSummary& summary) {
  if (options.consistency_parts < 2 || !summary.usable() || log.wheels.size() < 2) return;
  BatchOptions part_options = options;
  part_options.consistency_parts = 0;
  part_options.tyre_model = whole_log_model(options, summary);
  part_options.max_sigma_circumference_m = 1.0;  // the parts' sigma is compared, not judged
  CalibrationOptions part_common = common;
  part_common.judge_model_adequacy = false;
  // Nor is a part's dead reckoning: a part pulled off by the error the check looks for can
  // dead-reckon its stretch worse than nominal, and leaving it out would drop the very
  // disagreement to be measured. The option's maximum (101 times worse) turns the judgement off.
  part_common.max_dead_reckoning_increase = 100.0;

  PartsConsistency check;
  const double begin = log.wheels.t_s.front(), end = log.wheels.t_s.back();
  const int n = options.consistency_parts;
  for (int k = 0; k < n; ++k) {
    const double from = begin + (end - begin) * k / n;
    const double to = k + 1 == n ? end : begin + (end - begin) * (k + 1) / n;
    check.parts.push_back(fit_part(log, from, to, part_options, part_common));
  }
  check.fitted_parts = static_cast<std::size_t>(std::count_if(
      check.parts.begin(), check.parts.end(), [](const auto& p) { return p.fitted; }));
  const std::array<double, 2> whole = {summary.estimate.circumference_rl_m,
                                       summary.estimate.circumference_rr_m};
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  check.birge_ratio = {kNaN, kNaN};
  if (check.fitted_parts < 2) {
    check.verdict = fmt::format(
        "not checked: {} of the log's {} parts could be calibrated alone (a part needs motion "
        "and GNSS of its own; fewer parts, consistency_parts, make longer ones)",
        check.fitted_parts, n);
    summary.consistency = check;
    return;
  }
  const int dof = static_cast<int>(check.fitted_parts) - 1;
  check.bound = birge_ratio_bound(dof);
  for (std::size_t w = 0; w < 2; ++w) {
    double sum = 0.0;
    for (const PartsConsistency::Part& part : check.parts) {
      if (part.fitted) sum += std::pow((part.circumference_m[w] - whole[w]) / part.sigma_m[w], 2);
    }
    check.birge_ratio[w] = std::sqrt(sum / dof);
  }
  const std::string compared =
      fmt::format("{} of the log's {} parts of {:.0f} s, each calibrated alone,",
                  check.fitted_parts, n, (end - begin) / n);
  check.consistent = std::max(check.birge_ratio[0], check.birge_ratio[1]) <= check.bound;
  if (check.consistent) {
    check.verdict = fmt::format(
        "{} agree with the whole log within their sigma (R {:.2f} / {:.2f}, bound {:.2f})",
        compared, check.birge_ratio[0], check.birge_ratio[1], check.bound);
    summary.consistency = check;
    return;
  }
  check.sigma_scale = {std::max(1.0, check.birge_ratio[0]), std::max(1.0, check.birge_ratio[1])};
  widen_sigma(check.sigma_scale, summary);
  check.verdict = fmt::format(
      "{} disagree with the whole log beyond their sigma (R {:.2f} / {:.2f}, above {:.2f}): an "
      "error shared by stretches of the log moves the estimate further than its residuals show, "
      "most likely a GNSS error correlated over tens of seconds (state it: "
      "gnss_gauss_markov_sigma_m), or a tyre model that fits some of the drive and not the rest; "
      "the circumferences' sigma is widened by R",
      compared, check.birge_ratio[0], check.birge_ratio[1], check.bound);
  summary.consistency = check;
  std::vector<std::string> refused;
  for (std::size_t w = 0; w < 2; ++w) {
    EstimatedParameter& p = summary.parameters[w];
    if (p.sigma <= options.max_sigma_circumference_m) continue;
    p.identified = false;
    p.verdict = fmt::format(
        "widened by the parts' disagreement to {:.3g} mm, above max_sigma_circumference_m "
        "({:.3g} mm)",
        1e3 * p.sigma, 1e3 * options.max_sigma_circumference_m);
    refused.push_back(fmt::format("{} ({})", p.name, p.verdict));
  }
  if (!refused.empty()) {
    summary.termination = Termination::kNotIdentifiable;
    summary.identifiability = fmt::format("not identified: {}", fmt::join(refused, "; "));
    summary.message += "; not identified: " + check.verdict;
  } else {
    summary.note += (summary.note.empty() ? "" : "; ") + check.verdict;
  }
}

}  // namespace odocal::batch
