// The tyre models as the judges of a plain fit that was not chosen among them (tyre_model none
// by hand, and the other methods' judge, judge_model_adequacy): fitted as auto fits its
// candidates, the track width free in each. Where one fits the log better and is a tyre, or,
// where none is, one fits it decisively better, the plain circumferences are the ones the drive
// rolled on, and they carry their gap to that model's circumferences at rest in their sigma.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "batch_fit.hpp"

namespace odocal::batch {

std::optional<std::size_t> decisive_fit_that_cannot_stand(
    const std::vector<TyreCandidate>& candidates, double plain_bic) {
  // A tyre that fits the log better judges instead (or confirms the plain fit, under auto).
  const bool a_tyre_fits_better =
      std::any_of(candidates.begin(), candidates.end(),
                  [&](const TyreCandidate& c) { return c.can_stand() && c.bic < plain_bic; });
  if (a_tyre_fits_better) return std::nullopt;
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const TyreCandidate& c = candidates[i];
    if (c.can_stand() || !c.fitted() || !(c.bic < plain_bic - kDecisiveBic)) continue;
    if (!best || c.bic < candidates[*best].bic) best = i;
  }
  return best;
}

std::optional<std::size_t> tyre_fit_not_rejected(const std::vector<TyreCandidate>& candidates,
                                                 double plain_bic) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const TyreCandidate& c = candidates[i];
    if (!c.can_stand() || !c.fitted() || !(c.bic < plain_bic + kDecisiveBic)) continue;
    if (!best || c.bic < candidates[*best].bic) best = i;
  }
  return best;
}

double tie_gap_share(double excess) {
  if (!(excess >= 0.0)) return 1.0;
  const double weight = 1.0 / (1.0 + std::exp(0.5 * excess));
  return std::sqrt(weight * (1.0 - weight));
}

std::string how_it_fits(const TyreCandidate& candidate, double plain_bic) {
  if (!candidate.can_stand()) {
    return fmt::format("decisively better ({})",
                       candidate.tyre ? "every coefficient held" : "no tyre");
  }
  if (candidate.bic < plain_bic) return "better";
  return fmt::format("about as well (BIC within {:.0f})", kDecisiveBic);
}

std::string why_it_cannot_stand(const TyreCandidate& candidate) {
  if (!candidate.tyre) {
    return "is no tyre (coefficients beyond a road tyre's, or circumferences out of their band): "
           "no model here says surely where they lie; check vehicle.yaml's body and tyres, and "
           "the log's inputs";
  }
  if (candidate.every_coefficient_held) {
    return "identified none of its coefficients (each held at a car's value or at zero, which "
           "vehicle.yaml's body sets): drive more of what shows them (braking, accelerating and "
           "turning at speed), and check the body";
  }
  return "";
}

TyreJudgement judge_against_tyre_models(const CalibrationRun& run, const BatchOptions& options,
                                        const CalibrationOptions& common,
                                        const BatchSummary& unfitted,
                                        const GnssNoiseReport& plain_noise, double plain_bic) {
  TyreJudgement judgement{{}, plain_bic, std::nullopt};
  // Compared as auto compares them: under the noise the plain fit's residuals showed, where they
  // showed that the configured one is wrong.
  const std::optional<GnssNoiseModel> shared_noise = adapted_noise(plain_noise);
  // Each model with the track width free: a track that vehicle.yaml gets wrong turns the wheels'
  // heading with the curvature, which the load terms can mimic (an ideal lap on a track 10 %
  // wider than stated: the physical terms with the track held won the criterion by 5000 and put
  // the circumferences at rest 43 mm from the true ones; with it free, 1.5 mm, and no better
  // than the plain model). The tyre terms judge only what the geometry does not explain. The
  // driving states are measured only where a tyre model may be fitted.
  BatchOptions judging = options;
  judging.estimate_track_width = true;
  judging.tyre_model = TyreModelChoice::kAuto;
  int comparison_solves = 0;
  if (shared_noise || !options.estimate_track_width) {
    judgement.plain_bic = criterion_under(run, judging, common, unfitted, std::nullopt,
                                          shared_noise, comparison_solves);
  }
  for (const TyreTerms terms : kTyreCandidates) {
    TyreCandidate candidate{tyre_model_option(terms)};
    candidate.solves = comparison_solves;
    comparison_solves = 0;
    const std::optional<FitFacts> shared =
        shared_noise ? std::optional(solved_facts(run, judging, common, unfitted, terms,
                                                  shared_noise, candidate.solves))
                     : std::nullopt;
    BatchSummary fitted = unfitted;
    fit_model(run, judging, common, terms, fitted, {.finish = [&](const FitFacts& own) {
                const FitFacts& facts =
                    facts_to_judge_by(own, shared, unfitted.nominal, common.max_relative_change);
                candidate.judged_under_noise_shown = &facts != &own;
                candidate.bic = shared ? shared->bic : facts.bic;
                candidate.tyre =
                    facts.usable && is_tyre(facts, unfitted.nominal, common.max_relative_change);
                candidate.every_coefficient_held =
                    facts.usable && facts.free_tyre_coefficients == 0;
                candidate.needed = candidate.can_stand() && candidate.bic < judgement.plain_bic;
                if (facts.usable) candidate.circumference = facts.circumference;
                return false;
              }});
    candidate.solves += fitted.solves;
    judgement.candidates.push_back(candidate);
    if (candidate.needed) judgement.better = judgement.candidates.size() - 1;
    // The regression terms speak only where the physical ones fit the log better but cannot
    // stand (no tyre: a body that vehicle.yaml gets wrong; or every coefficient held): they
    // confirm that the plain model does not explain it and say where the circumferences at rest
    // lie.
    if (judgement.better || !(candidate.bic < judgement.plain_bic) || candidate.can_stand()) break;
  }
  if (!judgement.better)
    judgement.better = decisive_fit_that_cannot_stand(judgement.candidates, judgement.plain_bic);
  if (!judgement.better)
    judgement.better = tyre_fit_not_rejected(judgement.candidates, judgement.plain_bic);
  return judgement;
}

double TyreJudgement::gap_share() const {
  const TyreCandidate* fit = better_fit();
  return fit && fit->can_stand() ? tie_gap_share(fit->bic - plain_bic) : 1.0;
}

int TyreJudgement::solves() const {
  int total = 0;
  for (const TyreCandidate& candidate : candidates) total += candidate.solves;
  return total;
}

void say_a_tyre_model_fits_better(ModelAdequacy& adequacy, const TyreJudgement& judgement,
                                  const std::array<double, 2>& gap_m, const char* whose) {
  const TyreCandidate* better = judgement.better_fit();
  if (!adequacy.judged || !better) return;
  if (const double share = judgement.gap_share(); share < 1.0) {
    // Not decisively worse: the plain model explains the log as well as it did, but not surely
    // where the circumferences at rest lie.
    adequacy.verdict += fmt::format(
        "; tyre_model: {} fits it about as well (BIC {:.1f} against {:.1f}) and puts the "
        "circumferences at rest {:.3g} / {:.3g} mm from {}, of which their sigma carries "
        "{:.3g} / {:.3g} mm (the criteria's weight of the two)",
        better->model, better->bic, judgement.plain_bic, 1e3 * gap_m[0] / share,
        1e3 * gap_m[1] / share, whose, 1e3 * gap_m[0], 1e3 * gap_m[1]);
    return;
  }
  // Its own fit wandered under the configured noise: auto cannot choose it either. Or auto did
  // not need it: its circumferences at rest agree with the plain ones but were not identified.
  const char* advice = better->judged_under_noise_shown
                           ? "fitted under the GNSS noise that the residuals show (under the "
                             "configured one its fit did not settle): state that noise (gnss.csv's "
                             "sigma_m or gnss_sigma_m) and calibrate again"
                       : !better->needed
                           ? "auto keeps the plain fit, since that one's circumferences at rest "
                             "were not identified (max_sigma_circumference_m) and agree with these"
                           : "use the batch's tyre_model: auto";
  const std::string text =
      better->can_stand()
          ? fmt::format(
                "tyre_model: {} fits it better (BIC {:.1f} against {:.1f}) and puts the "
                "circumferences at rest {:.3g} / {:.3g} mm from {}, which their sigma carries; "
                "{}",
                better->model, better->bic, judgement.plain_bic, 1e3 * gap_m[0], 1e3 * gap_m[1],
                whose, advice)
          : fmt::format(
                "tyre_model: {} fits it decisively better (BIC {:.1f} against {:.1f}) and puts "
                "the circumferences at rest {:.3g} / {:.3g} mm from {}, which their sigma "
                "carries, but it {}",
                better->model, better->bic, judgement.plain_bic, 1e3 * gap_m[0], 1e3 * gap_m[1],
                whose, why_it_cannot_stand(*better));
  adequacy.verdict = adequacy.explains ? "the two-wheel model does not explain this log: " + text
                                       : adequacy.verdict + "; " + text;
  adequacy.explains = false;
}

BatchSummary fit_plain_carrying_gap(const CalibrationRun& run, const BatchOptions& options,
                                    const CalibrationOptions& common, const BatchSummary& unfitted,
                                    const TyreJudgement& judgement) {
  BatchSummary summary = unfitted;
  fit_model(run, options, common, std::nullopt, summary,
            {.rival_circumference = judgement.better_fit()->circumference,
             .rival_share = judgement.gap_share()});
  say_a_tyre_model_fits_better(summary.model_adequacy, judgement, summary.model_spread_m,
                               "the plain ones");
  return summary;
}

void fit_plain_judged(const CalibrationRun& run, const BatchOptions& options,
                      const CalibrationOptions& common, BatchSummary& summary) {
  const BatchSummary unfitted = summary;
  FitFacts plain;
  fit_model(run, options, common, std::nullopt, summary, {.finish = [&](const FitFacts& facts) {
              plain = facts;
              return true;
            }});
  if (!plain.usable) return;
  const TyreJudgement judgement =
      judge_against_tyre_models(run, options, common, unfitted, summary.gnss_noise, plain.bic);
  int other_solves = judgement.solves();
  TyreModelSelection selection;
  if (const TyreCandidate* better = judgement.better_fit()) {
    other_solves += summary.solves;
    summary = fit_plain_carrying_gap(run, options, common, unfitted, judgement);
    selection.plain_gap_to = better->model;
    selection.plain_gap_share = judgement.gap_share();
  }
  selection.compared = true;
  selection.judges_plain = true;
  selection.plain_bic = judgement.plain_bic;
  selection.candidates = judgement.candidates;
  selection.other_solves = other_solves;
  summary.tyre_selection = selection;
}

}  // namespace odocal::batch
