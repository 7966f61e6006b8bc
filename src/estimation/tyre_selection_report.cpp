// The report's line on the tyre models compared: which model stands and why, with every
// criterion (tyre_model auto), or how the tyre models judged a plain fit (tyre_model none).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "batch_fit.hpp"

namespace odocal::batch {
namespace {

// The model whose gap the plain circumferences carry (none: they carry none).
const TyreCandidate* gap_candidate(const TyreModelSelection& selection) {
  const auto gap =
      std::find_if(selection.candidates.begin(), selection.candidates.end(),
                   [&](const TyreCandidate& c) { return c.model == selection.plain_gap_to; });
  return gap == selection.candidates.end() ? nullptr : &*gap;
}

}  // namespace

std::string tyre_selection_report(const BatchSummary& summary) {
  const TyreModelSelection& selection = summary.tyre_selection;
  if (!selection.compared) return "";
  if (selection.judges_plain) {
    std::string criteria = fmt::format("plain {:.1f}", selection.plain_bic);
    for (const TyreCandidate& c : selection.candidates)
      criteria += fmt::format(", {} {:.1f}", c.model, c.bic);
    const TyreCandidate& last = selection.candidates.back();
    const TyreCandidate* gap = gap_candidate(selection);
    const std::string why =
        gap ? fmt::format("the {} terms fit the log {}: their gap is in the sigma", gap->model,
                          how_it_fits(*gap, selection.plain_bic))
        : !last.tyre ? fmt::format("the {} terms' fit was not a tyre", last.model)
        : last.every_coefficient_held
            ? fmt::format("the {} terms' fit identified none of their coefficients", last.model)
            : fmt::format("the {} terms do not fit the log better", last.model);
    return fmt::format("{:<13}plain, as configured ({}): BIC, the track width free in each: {}\n",
                       "tyre model", why, criteria);
  }
  std::string why =
      selection.chosen == "none" ? "the log does not need more" : "the log supports it";
  std::string named;  // the candidate that `why` names
  for (const TyreCandidate& c : selection.candidates) {
    if (c.model == selection.chosen) break;
    if (c.judged_under_noise_shown) {
      why = fmt::format(
          "the {} fit did not settle under the configured GNSS noise; under the noise that the "
          "residuals show it does: state that noise (gnss.csv's sigma_m or gnss_sigma_m)",
          c.model);
    } else if (!c.tyre) {
      why = fmt::format(
          "the {} fit was not a tyre: coefficients of percents, or a circumference "
          "out of its band",
          c.model);
    } else if (c.every_coefficient_held) {
      why = fmt::format(
          "the {} fit identified none of its coefficients (each held at a car's value or at "
          "zero)",
          c.model);
    } else if (!c.beyond_track) {
      why = fmt::format("the {} fit explains no more than the track width freed (BIC {:.1f}){}",
                        c.model, selection.free_track_bic,
                        selection.plain_track_free
                            ? ""
                            : ": check vehicle.yaml's track_width_m, or set estimate_track_width");
    } else if (!c.needed) {
      why = fmt::format(
          "the {} fit's circumferences at rest were not identified and agree with "
          "the plain fit's",
          c.model);
    } else if (!c.dead_reckons) {
      why = fmt::format(
          "with the {} fit the log dead-reckons worse than with the nominal "
          "parameters, with the plain fit it does not",
          c.model);
    } else {
      continue;
    }
    named = c.model;
    break;
  }
  if (const TyreCandidate* gap = gap_candidate(selection)) {
    const double plain_bic = selection.compared_plain_bic();  // as the gap was chosen
    const std::string which =
        gap->model == named ? std::string("it") : fmt::format("the {} fit", gap->model);
    why += fmt::format(
        "; {} fits the log {} all the same: the plain circumferences carry their gap to it in "
        "their sigma",
        which, how_it_fits(*gap, plain_bic));
  }
  if (selection.body_in_doubt()) {
    why += fmt::format(
        "; the {} terms, which need no body, put the circumferences at rest {:.1f} of their "
        "combined sigma away: the physical ones carry that gap in their sigma; check "
        "vehicle.yaml's body",
        selection.chosen_gap_to, selection.chosen_gap_sigmas);
  }
  std::string criteria = fmt::format("plain {:.1f}", selection.plain_bic);
  if (std::isfinite(selection.free_track_bic))
    criteria += fmt::format(", plain with the track free {:.1f}", selection.free_track_bic);
  std::string chosen = selection.plain_track_free ? "plain, the track width free" : "plain";
  for (const TyreCandidate& c : selection.candidates) {
    criteria += fmt::format(", {} {:.1f}", c.model, c.bic);
    if (std::isfinite(c.free_track_bic)) {
      criteria += fmt::format(" (the track {}; {} {:.1f}", c.track_free ? "free" : "held",
                              c.track_free ? "held" : "free",
                              c.track_free ? c.held_track_bic : c.free_track_bic);
      if (std::isfinite(c.held_track_score_m)) {
        criteria += fmt::format("; dead-reckoning the log {:.1f} m held, {:.1f} m free",
                                c.held_track_score_m, c.free_track_score_m);
      }
      criteria += ")";
    }
    if (c.model == selection.chosen)
      chosen = c.model + (c.track_free ? ", the track width free" : "");
  }
  // A freed track far from vehicle.yaml's, beyond its sigma, says that one of them is wrong.
  // Not a small shift: a freed track takes up some of a tyre model's misfit too (3 laps of
  // Hockenheim, the grip-sharing driver, front-driven: 9 mm, 3.1 sigma, on a track stated right).
  constexpr double kTrackShiftWorthNaming = 0.02;
  const EstimatedParameter* track =
      summary.parameters.size() > 2 ? &summary.parameters[2] : nullptr;
  const double stated = summary.nominal.track_width_m;
  if (track && track->estimated && track->identified &&
      std::abs(track->value - stated) > 3.0 * track->sigma &&
      std::abs(track->value / stated - 1.0) > kTrackShiftWorthNaming) {
    why += fmt::format(
        "; the log puts the track at {:.4f} m (1-sigma {:.4f}), vehicle.yaml at {:.4f}: check "
        "track_width_m",
        track->value, track->sigma, stated);
  }
  return fmt::format("{:<13}{} ({}): BIC {}\n", "tyre model", chosen, why, criteria);
}

}  // namespace odocal::batch
