// The plain fit with its track width under a prior, where its held track's share would only
// overstate its sigma (docs/batch-calibration.md, "The track under its prior").
#include <cmath>
#include <utility>

#include "batch_fit.hpp"
#include "calibration_run.hpp"

namespace odocal::batch {

namespace {

// More than this share of either circumference's sigma: the share is what the sigma is made of.
constexpr double kMaterialShare = 0.5;

bool track_prior_helps(const BatchOptions& options, const BatchSummary& fitted) {
  const TyreModelSelection& selection = fitted.tyre_selection;
  // Only where the tyre models judged the plain fit, none fits the log better (no gap carried)
  // and the track was not in doubt: load transfer moves the track the wheels roll on, and a
  // fitted track then takes the turns' misfit (three load-transfer plain fits, 5-8 sigma off).
  const bool judged_plain = selection.compared && selection.chosen == "none" &&
                            fitted.tyre_model.plain() && !std::isfinite(selection.free_track_bic);
  const bool no_gap = fitted.model_spread_m[0] == 0.0 && fitted.model_spread_m[1] == 0.0;
  const bool material = fitted.track_sigma_m[0] > kMaterialShare * fitted.sigma_rl_m() ||
                        fitted.track_sigma_m[1] > kMaterialShare * fitted.sigma_rr_m();
  // The fixes' noise checked against their residuals (adapt_gnss_noise, not reverted): under a
  // noise taken as given the fixes may pull the scale far more firmly than they can, and a
  // fitted track follows them (bench/honest_sigma.cpp, configured noise).
  const GnssNoiseReport& gnss = fitted.gnss_noise;
  const bool noise_checked = options.adapt_gnss_noise && !gnss.reverted;
  return judged_plain && no_gap && fitted.model_adequacy.explains && material && noise_checked &&
         !options.estimate_track_width && options.track_width_uncertainty > 0.0;
}

}  // namespace

bool fit_track_under_prior(CalibrationRun& run, const BatchOptions& options,
                           const CalibrationOptions& common, const BatchSummary& unfitted,
                           BatchSummary& summary) {
  if (!track_prior_helps(options, summary)) return false;
  BatchSummary refit = unfitted;
  fit_model(run, options, common, std::nullopt, refit, {.track_prior = true});
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
