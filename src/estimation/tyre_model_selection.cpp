// tyre_model auto: the plain fit, then the tyre models in turn, each fitted on its own exactly as
// its own choice fits it; a candidate replaces the best fit so far when its information criterion
// is lower and it is a tyre. The physical terms come first, and the regression terms are tried
// only where the physical ones did not replace the plain fit: a lower criterion from seven free
// coefficients says that they follow this log's wheel speeds more closely, not that they
// extrapolate better to the circumference at rest, which is what is asked (on 3 laps of
// Hockenheim with a front-driven car, the regression terms win the criterion and land 9 mm off,
// the physical ones 2 mm); where the physical terms win the criterion and confirm the plain fit,
// the plain fit stands and the regression terms are not tried. The result is one of the fits, never
// a blend (a log the plain model explains calibrates exactly as under none). One problem lives at a
// time (a long log's memory is its problem's): the plain fit is finished and freed first, and a
// candidate is finished (noise adaptation, covariance) only when it beats the best fit so far.
// The criteria are compared under one GNSS noise model: the configured one, or the one the plain
// fit's residuals showed where it adapted it (each model then solved once more, for its criterion).
// Where none stands and one that cannot stand (no tyre, or every coefficient held) fits the log
// decisively better, the plain circumferences carry their gap to it
// (decisive_fit_that_cannot_stand); else to a tyre that the log does not decisively reject
// (tyre_fit_not_rejected). The same candidates judge a plain fit
// that was not chosen among them: tyre_model_judge.cpp.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "batch_fit.hpp"

namespace odocal::batch {
namespace {

// A fit whose answer stands on its own: converged, or converged without identifying the
// circumferences to the required sigma (which the summary says). Not: no convergence, a solver
// failure, an implausible answer.
bool sound(const BatchSummary& summary) {
  return summary.termination == Termination::kConverged ||
         summary.termination == Termination::kNotIdentifiable;
}

// The dependence that a track width off by a fraction leaves in the plain fit's residuals.
bool heading_follows_curvature(const ModelAdequacy& adequacy) {
  return std::any_of(adequacy.dependences.begin(), adequacy.dependences.end(),
                     [](const ResidualDependence& d) {
                       return d.residual == "heading" && d.quantity == "curvature" && d.counts();
                     });
}

// Whether a fit with the track freed took the geometry's share and not the model's misfit: its
// track pinned down (sigma within max_sigma_track_width_m), or its heading residual no longer
// following the curvature. On the racing line, rear-driven, with a driver who fishtails out of
// the corners, the physical terms put the freed track at 2.12 m (sigma 78 mm) on a stated and
// true 1.6 m, their heading residual still following the curvature (rho 0.45); on the realistic
// urban drive on a track 10 % wider than stated, at 1.7666 m (sigma 13 mm), the log explained.
bool geometry_explained(const BatchSummary& fitted) {
  const bool identified = fitted.parameters.size() > 2 && fitted.parameters[2].identified;
  return identified || !heading_follows_curvature(fitted.model_adequacy);
}

// Where a fit with vehicle.yaml's track explains the geometry (its heading residual does not
// follow the curvature), its whole-log dead-reckoning score: the freed track stands against it
// only by dead-reckoning the log better, which is what the track is for. Where it does not, the
// stated track is not compared: its dead reckoning need not show a wrong track (the realistic
// circuit, front-driven, on a track 6 % narrower than stated, seed 1: 21.4 m held, 21.7 m free,
// the held heading residual following the curvature at rho 0.71, and the circumference at rest
// 2.1 mm off at a sigma of 0.7 mm held, 0.3 mm free).
std::optional<double> stated_track_score(CalibrationRun& run, const BatchSummary& held) {
  if (heading_follows_curvature(held.model_adequacy)) return std::nullopt;
  return dead_reckoning_score(run.dead_reckon(held));
}

}  // namespace

FitFacts solved_facts(const CalibrationRun& run, const BatchOptions& options,
                      const CalibrationOptions& common, const BatchSummary& unfitted,
                      std::optional<TyreTerms> terms, const std::optional<GnssNoiseModel>& noise,
                      int& solves) {
  FitFacts solved;
  BatchSummary scratch = unfitted;
  fit_model(run, options, common, terms, scratch,
            {.finish =
                 [&](const FitFacts& facts) {
                   solved = facts;
                   return false;
                 },
             .noise = noise});
  solves += scratch.solves;
  return solved;
}

bool is_tyre(const FitFacts& facts, const OdometryParams& nominal, double max_change) {
  return facts.max_tyre_effect <= kMaxTyreEffect &&
         std::abs(facts.circumference[0] / nominal.circumference_rl_m - 1.0) <= max_change &&
         std::abs(facts.circumference[1] / nominal.circumference_rr_m - 1.0) <= max_change;
}

const FitFacts& facts_to_judge_by(const FitFacts& own, const std::optional<FitFacts>& shared,
                                  const OdometryParams& nominal, double max_change) {
  const auto can_stand = [&](const FitFacts& facts) {
    return facts.usable && facts.free_tyre_coefficients > 0 && is_tyre(facts, nominal, max_change);
  };
  return own.usable && own.wandered && shared && can_stand(*shared) ? *shared : own;
}

std::optional<GnssNoiseModel> adapted_noise(const GnssNoiseReport& report) {
  if (!report.adapted || report.reverted || !(report.configured_sigma_m > 0.0)) return std::nullopt;
  GnssNoiseModel noise;
  noise.white_scale = report.white_sigma_m / report.configured_sigma_m;
  noise.gauss_markov_sigma_m = report.model_gauss_markov_sigma_m;
  if (report.model_gauss_markov_tau_s > 0.0)
    noise.gauss_markov_tau_s = report.model_gauss_markov_tau_s;
  return noise;
}

bool fit_auto(CalibrationRun& run, const BatchOptions& options, const CalibrationOptions& common,
              BatchSummary& summary) {
  const BatchSummary unfitted = summary;
  FitFacts plain;
  fit_model(run, options, common, std::nullopt, summary, {.finish = [&](const FitFacts& facts) {
              plain = facts;
              return true;
            }});
  if (!plain.usable) return false;
  int all_solves = summary.solves;
  // The criteria are compared under one GNSS noise model. Where the plain fit's residuals showed
  // that the configured one is wrong, it is the one they showed: under a configured noise that
  // does not describe the GNSS error (a correlated error of metres configured as 0.1 m of white
  // noise), the criterion rewards whatever follows part of that error, and on an ideal circuit,
  // with no tyre effect in it, tyre terms won and moved the circumferences 2 mm at a sigma of
  // 0.43 mm (bench/honest_sigma.cpp, run 28). Each model is solved once more under that noise for
  // its criterion alone; the fit that is chosen is the model's own, from the configured noise, as
  // its own choice fits it (solved under the plain fit's noise, which took in the plain model's
  // misfit, the physical terms' circumference moved 12 mm in
  // TyreModelBatch.RecoversKnownCoefficientsWhereThePlainModelIsBiased).
  const std::optional<GnssNoiseModel> shared_noise = adapted_noise(summary.gnss_noise);
  const auto criterion_under_shared_noise = [&](std::optional<TyreTerms> terms, int& solves) {
    return criterion_under(run, options, common, unfitted, terms, *shared_noise, solves);
  };
  if (shared_noise) plain.bic = criterion_under_shared_noise(std::nullopt, all_solves);
  TyreModelSelection selection;
  selection.compared = true;
  selection.plain_bic = plain.bic;
  // A track width that vehicle.yaml gets wrong turns the wheels' heading with the curvature, which
  // the load terms mimic as load transfer (an ideal lap on a track 10 % wider than stated: the
  // physical terms won the criterion by 5000 and put the circumferences at rest 43 mm off, at a
  // sigma of 3.3 mm). Where the track is held and in doubt, a tyre model that the plain model
  // with the track freed matches or beats on the criterion is not taken: the geometry explains
  // the log. In doubt: where the plain fit's heading residual follows the curvature, or (below)
  // where a tyre model that wins the criterion leaves it so, or is no tyre. Only then: on the
  // 10-hour drive with a Doppler column the freed plain fit took 33 s.
  const bool track_held = !options.estimate_track_width;
  BatchOptions free_track = options;
  free_track.estimate_track_width = true;
  bool track_in_doubt = false;
  const auto doubt_the_track = [&] {
    track_in_doubt = true;
    selection.free_track_bic =
        criterion_under(run, free_track, common, unfitted, std::nullopt, shared_noise, all_solves);
  };
  if (track_held && heading_follows_curvature(summary.model_adequacy)) doubt_the_track();
  const double max_change = common.max_relative_change;
  const double max_variance = options.max_sigma_circumference_m * options.max_sigma_circumference_m;
  // As reported: after the plain fit's noise adaptation.
  const bool plain_identified = summary.parameters.size() >= 2 &&
                                summary.parameters[0].identified &&
                                summary.parameters[1].identified;
  // A tyre model's circumferences at rest that agree with the identified plain fit's: its sigma
  // widened by the gap between them would still be identified.
  const auto agrees_with_plain = [&](const std::array<double, 2>& at_rest) {
    if (!plain_identified) return false;
    for (std::size_t wheel = 0; wheel < 2; ++wheel) {
      const double gap = at_rest[wheel] - plain.circumference[wheel];
      const double sigma = summary.parameters[wheel].sigma;  // as reported
      if (sigma * sigma + gap * gap > max_variance) return false;
    }
    return true;
  };
  double best_bic = plain.bic;
  bool finished = false;  // run.finish has scored `summary`
  // The physical terms' circumferences, where they were solved: the regression terms after them
  // carry their gap to them in their sigma. Both extrapolate to rest from the same drive; where
  // they disagree, neither extrapolation is surer than that (3 laps of Hockenheim, rear-driven,
  // with the Doppler speed: the regression terms -11.7 mm at sigma 1.6 mm, the physical ones,
  // no tyre there, +22.9 mm).
  std::optional<std::array<double, 2>> physical_circumference;
  for (const TyreTerms terms : kTyreCandidates) {
    if (selection.chosen != "none") break;
    TyreCandidate candidate;
    BatchSummary fitted;
    bool accepted = false;
    // Each criterion is taken once: with the track held (under the configured noise, the held
    // fit's own) and, where the track is in doubt, free.
    std::optional<double> held_criterion, free_criterion;
    // Those fits' facts under the shared noise, and the model's own fit's, as last chosen on.
    std::optional<FitFacts> held_shared, free_shared, own_facts;
    bool keep_track_held = false;
    // An accepted fit with the track freed, while the same model is fitted with it held.
    struct Freed {
      BatchSummary fit;
      TyreCandidate candidate;
      std::optional<std::array<double, 2>> physical_circumference;
      double score_m;
    };
    std::optional<Freed> freed;
    for (bool fit_again = true; fit_again;) {
      fit_again = false;
      candidate = TyreCandidate{tyre_model_option(terms)};
      int comparison_solves = 0;
      if (shared_noise && !held_criterion) {
        held_shared =
            solved_facts(run, options, common, unfitted, terms, *shared_noise, comparison_solves);
        held_criterion = held_shared->bic;
      }
      // Where the track is in doubt, a tyre model is fitted with it free too, and stands the way
      // that the criterion prefers: slipping tyres on a track that vehicle.yaml gets wrong beat
      // the freed plain model, and with the track held the load terms took the track's share as
      // well (the realistic circuit, rear-driven, on a track 10 % wider than stated: the
      // physical terms 35.9 mm off at a sigma of 4.6 mm held, +2.4 mm at 4.5 mm free).
      const BatchOptions* fitting = &options;
      if (track_in_doubt) {
        if (!held_criterion) {
          held_criterion = criterion_under(run, options, common, unfitted, terms, std::nullopt,
                                           comparison_solves);
        }
        if (!free_criterion) {
          free_shared = solved_facts(run, free_track, common, unfitted, terms, shared_noise,
                                     comparison_solves);
          free_criterion = free_shared->bic;
          if (!shared_noise) free_shared.reset();  // the configured noise's: no other noise
        }
        candidate.held_track_bic = *held_criterion;
        candidate.free_track_bic = *free_criterion;
        candidate.track_free = !keep_track_held && *free_criterion < *held_criterion;
        if (candidate.track_free) fitting = &free_track;
      }
      const std::optional<double> shared_bic = candidate.track_free ? free_criterion
                                               : shared_noise       ? held_criterion
                                                                    : std::nullopt;
      const auto choose = [&](const FitFacts& facts) {
        own_facts = facts;
        candidate.bic = shared_bic.value_or(facts.bic);
        if (!candidate.track_free && facts.usable) held_criterion = candidate.bic;
        if (!facts.usable) return false;
        candidate.circumference = facts.circumference;
        if (terms == TyreTerms::kPhysical) physical_circumference = facts.circumference;
        candidate.tyre = is_tyre(facts, summary.nominal, max_change);
        candidate.every_coefficient_held = facts.free_tyre_coefficients == 0;
        const bool wins = candidate.can_stand() && candidate.bic < best_bic;
        // Not fitted (NaN): nothing to refuse on.
        candidate.beyond_track = !wins || !(selection.free_track_bic <= candidate.bic);
        const bool better = wins && candidate.beyond_track;
        // Circumferences at rest that the log cannot pin down (an extrapolation from the states
        // driven: on a long drive the BIC prefers effects of a few 1e-4) are no better answer
        // than an identified plain fit that they agree with: one that, its sigma widened by the
        // gap between the two, would still be identified. Agreeing within the candidate's own
        // 3 sigma is not enough: with a sigma of 3 mm that let a plain fit stand 11 mm off at a
        // sigma of 0.6 mm (the realistic urban drive, rear-driven). Where they disagree, the
        // candidate stands, unidentified, rather than a confident wrong answer.
        const bool unidentified = std::max(facts.circumference_variance[0],
                                           facts.circumference_variance[1]) > max_variance;
        candidate.needed = !better || !unidentified || !agrees_with_plain(facts.circumference);
        return better && candidate.needed;
      };
      fitted = unfitted;
      accepted =
          fit_model(run, *fitting, common, terms, fitted,
                    {.finish = choose,
                     .rival_circumference =
                         terms == TyreTerms::kRegression ? physical_circumference : std::nullopt});
      candidate.solves = fitted.solves + comparison_solves;
      all_solves += candidate.solves;
      // The plain fit's residuals need not show a wrong track: where its GNSS noise adaptation
      // took a misfit of metres in as correlated GNSS error, they did not (the realistic circuit,
      // rear-driven, on a track 6 % narrower than stated, seeds 2 and 3: rho 0.25 and 0.29; the
      // plain fit 87 mm off at a sigma of 1.7 mm, the physical terms held 19.6 mm at 5.1 mm, or
      // no tyre). A tyre model that wins the criterion shows it: by leaving the heading residual
      // following the curvature, or by being no tyre. It is then fitted again, both ways.
      const bool wins_as_no_tyre = !candidate.tyre && candidate.bic < best_bic;
      const bool leaves_the_curvature =
          accepted && heading_follows_curvature(fitted.model_adequacy);
      if (track_held && !track_in_doubt && (wins_as_no_tyre || leaves_the_curvature)) {
        doubt_the_track();
        fit_again = true;
      }
      if (accepted && candidate.track_free) {
        // A freed track that explains the geometry still takes up some of the model's misfit
        // where vehicle.yaml's is right (3 laps of Hockenheim, the grip-sharing driver,
        // front-driven: 9 mm off a right track, its whole-log dead reckoning 31 -> 42 m). The
        // model is fitted with the track held too: see stated_track_score.
        if (geometry_explained(fitted)) {
          const double score_m = dead_reckoning_score(run.dead_reckon(fitted));
          freed = Freed{std::move(fitted), candidate, physical_circumference, score_m};
        }
        keep_track_held = true;
        fit_again = true;
      }
    }
    if (freed) {
      const std::optional<double> held_score_m =
          accepted ? stated_track_score(run, fitted) : std::nullopt;
      if (!held_score_m || !(*held_score_m <= freed->score_m)) {
        fitted = std::move(freed->fit);
        candidate = freed->candidate;
        physical_circumference = freed->physical_circumference;
        accepted = true;
      }
      if (held_score_m) {
        candidate.held_track_score_m = *held_score_m;
        candidate.free_track_score_m = freed->score_m;
      }
    }
    // The facts' sigma above is the bare solve's; the one reported carries the GNSS noise
    // adapted and the shares of what the fit takes as known (the body, held coefficients, the
    // accelerometer's offset), and it too must be identified for the fit to be needed (the
    // ideal circuit, its wheels recounted with 5e-4 s^2/m of load, 1 m fixes, limit 0.15 mm:
    // the physical terms 0.05 mm bare, 0.18 mm reported, refused, where the plain fit agreed
    // within 0.13 mm).
    if (accepted) {
      const double widest = std::max(fitted.parameters[0].sigma, fitted.parameters[1].sigma);
      if (widest * widest > max_variance && agrees_with_plain(candidate.circumference)) {
        candidate.needed = false;
        accepted = false;
      }
    }
    // Not chosen, it may still judge the plain fit (below): by its fit under the noise shown
    // where its own cannot stand (facts_to_judge_by).
    if (!accepted && own_facts) {
      const FitFacts& judged =
          facts_to_judge_by(*own_facts, candidate.track_free ? free_shared : held_shared,
                            summary.nominal, max_change);
      if (&judged != &*own_facts) {
        candidate.judged_under_noise_shown = true;
        candidate.tyre = true;
        candidate.every_coefficient_held = false;
        candidate.circumference = judged.circumference;
        if (terms == TyreTerms::kPhysical) physical_circumference = judged.circumference;
      }
    }
    // A tyre model that won the criterion and agrees with the plain fit confirms it: the
    // regression terms after it could only stand by disagreeing with both, and the physics
    // carries the circumference at rest better than they do.
    const bool confirms_plain = !candidate.needed;
    if (accepted) {
      // A lower BIC is not enough: with a million samples it prefers effects of a few 1e-5 (an
      // ideal 100-lap circuit), whose whole-log dead reckoning can be worse than the nominal
      // parameters' where the best fit's so far is not. Scored both ways, the sound one stands.
      run.finish(fitted);
      if (!finished) run.finish(summary);
      finished = true;
      candidate.dead_reckons = sound(fitted) || !sound(summary);
      if (candidate.dead_reckons) {
        summary = std::move(fitted);
        best_bic = candidate.bic;
        selection.chosen = candidate.model;
      }
    }
    selection.candidates.push_back(candidate);
    if (confirms_plain) break;
  }
  if (selection.chosen == tyre_model_option(TyreTerms::kPhysical)) {
    summary.tyre_selection = selection;
    if (witness_physical_fit(run, selection.candidates.back().track_free ? free_track : options,
                             common, unfitted, summary, all_solves)) {
      run.finish(summary);
    }
    selection = summary.tyre_selection;
  } else if (selection.chosen == tyre_model_option(TyreTerms::kRegression) &&
             physical_circumference) {
    selection.chosen_gap_to = tyre_model_option(TyreTerms::kPhysical);
  }
  // Where no tyre model stands and the track freed fits the log better, the plain model stands
  // with it free: the circumferences held the track's misfit otherwise, and dead reckoning turns
  // with the track (3 ideal laps on a track 10 % wider than stated: held -0.51 mm at a sigma of
  // 0.42 mm; free -0.12 mm at 0.12 mm, the track at 1.7601 m).
  if (selection.chosen == "none" && selection.free_track_bic < selection.plain_bic) {
    BatchSummary fitted = unfitted;
    fit_model(run, free_track, common, std::nullopt, fitted);
    all_solves += fitted.solves;
    if (finished) run.finish(fitted);
    // As for a tyre model's; dead-reckoned only where the rest holds (finish() already did it).
    const auto dead_reckons_better = [&] {
      const std::optional<double> held_score_m = stated_track_score(run, summary);
      return !held_score_m ||
             dead_reckoning_score(finished ? fitted.after : run.dead_reckon(fitted)) <
                 *held_score_m;
    };
    if (geometry_explained(fitted) && (sound(fitted) || !sound(summary)) && dead_reckons_better()) {
      summary = std::move(fitted);
      selection.plain_track_free = true;
    }
  }
  if (selection.chosen == "none") {
    const double plain_bic = selection.compared_plain_bic();
    std::optional<std::size_t> better =
        decisive_fit_that_cannot_stand(selection.candidates, plain_bic);
    if (!better) better = tyre_fit_not_rejected(selection.candidates, plain_bic);
    if (better) {
      const TyreJudgement judgement{selection.candidates, plain_bic, better};
      BatchSummary judged = fit_plain_carrying_gap(
          run, selection.plain_track_free ? free_track : options, common, unfitted, judgement);
      all_solves += judged.solves;
      if (finished) run.finish(judged);
      summary = std::move(judged);
      selection.plain_gap_to = judgement.better_fit()->model;
      selection.plain_gap_share = judgement.gap_share();
    }
  }
  selection.other_solves = all_solves - summary.solves;
  summary.tyre_selection = selection;
  return finished;
}

}  // namespace odocal::batch
