// The plain fit with its track width under a prior, where its held track's share would only
// overstate its sigma (docs/batch-calibration.md, "The track under its prior").
#include <cmath>
#include <optional>
#include <utility>

#include "batch_fit.hpp"
#include "calibration_run.hpp"

namespace odocal::batch {

namespace {

// More than this share of either circumference's sigma: the share is what the sigma is made of.
constexpr double kMaterialShare = 0.5;

// The tyre model that fits the log about as well as the plain one (tie_gap_share), as the
// judgement that found it; none where no model ties.
std::optional<TyreJudgement> tie(const TyreModelSelection& selection) {
  if (!(selection.plain_gap_share > 0.0 && selection.plain_gap_share < 1.0)) return std::nullopt;
  for (std::size_t i = 0; i < selection.candidates.size(); ++i) {
    if (selection.candidates[i].model == selection.plain_gap_to)
      return TyreJudgement{selection.candidates, selection.compared_plain_bic(), i};
  }
  return std::nullopt;
}

bool track_prior_helps(const BatchOptions& options, const BatchSummary& fitted) {
  const TyreModelSelection& selection = fitted.tyre_selection;
  // Only where the tyre models judged the plain fit, none fits the log better (no gap carried,
  // or a tie's share of it) and the track was not in doubt: load transfer moves the track the
  // wheels roll on, and a fitted track then takes the turns' misfit (three load-transfer plain
  // fits, 5-8 sigma off).
  const bool judged_plain = selection.compared && selection.chosen == "none" &&
                            fitted.tyre_model.plain() && !std::isfinite(selection.free_track_bic);
  const bool at_most_a_tie = (fitted.model_spread_m[0] == 0.0 && fitted.model_spread_m[1] == 0.0) ||
                             tie(selection).has_value();
  const bool material = fitted.track_sigma_m[0] > kMaterialShare * fitted.sigma_rl_m() ||
                        fitted.track_sigma_m[1] > kMaterialShare * fitted.sigma_rr_m();
  // The fixes' noise checked against their residuals (adapt_gnss_noise, not reverted): under a
  // noise taken as given the fixes may pull the scale far more firmly than they can, and a
  // fitted track follows them (bench/honest_sigma.cpp, configured noise).
  const GnssNoiseReport& gnss = fitted.gnss_noise;
  const bool noise_checked = options.adapt_gnss_noise && !gnss.reverted;
  return judged_plain && at_most_a_tie && fitted.model_adequacy.explains && material &&
         noise_checked && !options.estimate_track_width && options.track_width_uncertainty > 0.0;
}

}  // namespace

bool fit_track_under_prior(CalibrationRun& run, const BatchOptions& options,
                           const CalibrationOptions& common, const BatchSummary& unfitted,
                           BatchSummary& summary) {
  if (!track_prior_helps(options, summary)) return false;
  BatchSummary refit = unfitted;
  // A tie's gap is the two models' difference under one track: carried as the held fits found
  // it, since under the prior the rival's circumferences would move with the track as the plain
  // ones do.
  const std::optional<TyreJudgement> tied = tie(summary.tyre_selection);
  FitControls controls{.track_prior = true};
  if (tied) controls.carried_spread_m = summary.model_spread_m;
  fit_model(run, options, common, std::nullopt, refit, controls);
  if (tied)
    say_a_tyre_model_fits_better(refit.model_adequacy, *tied, refit.model_spread_m,
                                 "the plain ones");
  run.finish(refit);
  // The same log and model: its model must still explain the log for the prior to stand. Where
  // the held fit was not identified either, the refit's is the sigma to report, identified or
  // not (the held track's share alone left it unidentified: bench/honest_sigma.cpp, run 3,
  // 11.86 mm held, 2.24 mm under the prior).
  const bool neither_identified = summary.termination == Termination::kNotIdentifiable &&
                                  refit.termination == Termination::kNotIdentifiable;
  if (!(refit.usable() || neither_identified) || !refit.model_adequacy.explains) {
    summary.tyre_selection.other_solves += refit.solves;
    return false;
  }
  refit.tyre_selection = summary.tyre_selection;
  refit.tyre_selection.other_solves += summary.solves;
  summary = std::move(refit);
  return true;
}

}  // namespace odocal::batch
