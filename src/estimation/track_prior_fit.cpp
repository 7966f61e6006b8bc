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

// fit_track_under_prior's gate, for any held plain fit that the tyre models judged: none fits the
// log better (no gap carried, or a tie's share of it) and its model explains it (load transfer
// moves the track the wheels roll on, and a fitted track then takes the turns' misfit: three
// load-transfer plain fits, 5-8 sigma off), the fixes' noise was checked against their residuals
// (adapt_gnss_noise, not reverted: under a noise taken as given the fixes may pull the scale far
// more firmly than they can, and a fitted track follows them; bench/honest_sigma.cpp, configured
// noise), and the held track's share is material.
bool prior_may_stand(const BatchOptions& options, const HeldPlainFit& held) {
  const bool material = held.track_share_m[0] > kMaterialShare * held.sigma_m[0] ||
                        held.track_share_m[1] > kMaterialShare * held.sigma_m[1];
  const bool noise_checked = options.adapt_gnss_noise && !held.noise.reverted;
  return held.at_most_a_tie && held.explains && material && noise_checked &&
         !options.estimate_track_width && options.track_width_uncertainty > 0.0;
}

bool track_prior_helps(const BatchOptions& options, const BatchSummary& fitted) {
  const TyreModelSelection& selection = fitted.tyre_selection;
  // Only where the tyre models judged the plain fit and auto did not doubt the track.
  const bool judged_plain = selection.compared && selection.chosen == "none" &&
                            fitted.tyre_model.plain() && !std::isfinite(selection.free_track_bic);
  const bool at_most_a_tie = (fitted.model_spread_m[0] == 0.0 && fitted.model_spread_m[1] == 0.0) ||
                             tie(selection).has_value();
  return judged_plain && prior_may_stand(options, {at_most_a_tie,
                                                   fitted.model_adequacy.explains,
                                                   fitted.gnss_noise,
                                                   fitted.track_sigma_m,
                                                   {fitted.sigma_rl_m(), fitted.sigma_rr_m()}});
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
  // Solved from the start under the noise the held fit's residuals showed (the same log and
  // model: adapting it again from the configured one found the same noise in more solves).
  FitControls controls{.noise = adapted_noise(summary.gnss_noise), .track_prior = true};
  if (tied) controls.carried_spread_m = summary.model_spread_m;
  fit_model(run, options, common, std::nullopt, refit, controls);
  // Where the refit's residuals showed no other noise, how the noise was found is the held fit's.
  if (controls.noise && !refit.gnss_noise.adapted) refit.gnss_noise = summary.gnss_noise;
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
  if (!(refit.usable() || neither_identified) || !refit.model_adequacy.explains ||
      refit.gnss_noise.reverted) {
    summary.tyre_selection.other_solves += refit.solves;
    return false;
  }
  refit.tyre_selection = summary.tyre_selection;
  refit.tyre_selection.other_solves += summary.solves;
  summary = std::move(refit);
  return true;
}

std::optional<JudgedTrack> judge_track_under_prior(const CalibrationRun& run,
                                                   const BatchOptions& options,
                                                   const CalibrationOptions& common,
                                                   const BatchSummary& unfitted,
                                                   const HeldPlainFit& held) {
  if (!prior_may_stand(options, held)) return std::nullopt;
  BatchSummary refit = unfitted;
  bool usable = false;
  fit_model(run, options, common, std::nullopt, refit,
            {.finish =
                 [&](const FitFacts& facts) {
                   usable = facts.usable;
                   return usable;
                 },
             .noise = adapted_noise(held.noise),
             .track_prior = true});
  const EstimatedParameter& track = refit.parameters.at(2);
  // The circumferences' own sigma need not pass the batch's refusal threshold (the held fit's
  // share may be what kept it above: bench/honest_sigma.cpp, run 2), but it must be known.
  const bool known = std::isfinite(refit.parameters.at(0).sigma) &&
                     std::isfinite(refit.parameters.at(1).sigma) && track.identified &&
                     track.sigma > 0.0;
  if (!usable || !known || refit.gnss_noise.reverted || !refit.model_adequacy.explains)
    return std::nullopt;
  // track_sigma_m is |g| sigma_t (summarise), so the factor scales it to the held track's share.
  const double held_offset_m = unfitted.nominal.track_width_m - track.value;
  const double factor = std::hypot(held_offset_m, track.sigma) / track.sigma;
  return JudgedTrack{
      track.value, track.sigma, {factor * refit.track_sigma_m[0], factor * refit.track_sigma_m[1]}};
}

}  // namespace odocal::batch
