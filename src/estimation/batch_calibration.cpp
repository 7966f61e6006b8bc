// The batch calibration (docs/batch-calibration.md): one fit of the plain model or of a tyre
// model's terms through its steps (batch_solve_steps.hpp), the model-adequacy judgement for the
// other methods, and calibrate_batch choosing how to fit.
#include "odocal/estimation/batch_calibration.hpp"

#include <ceres/ceres.h>
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>

#include "batch_consistency.hpp"
#include "batch_detections.hpp"
#include "batch_fit.hpp"
#include "batch_problem.hpp"
#include "batch_solve_steps.hpp"
#include "calibration_run.hpp"
#include "doppler_scale.hpp"
#include "odocal/error.hpp"
#include "second_fit.hpp"

namespace odocal {

using batch::BatchProblem;

bool batch::fit_model(const CalibrationRun& run, const BatchOptions& options,
                      const CalibrationOptions& common, std::optional<TyreTerms> terms,
                      BatchSummary& summary, const FitControls& controls) {
  BatchProblem batch(run.log(), run.batch_wheels(), run.reference(), options, common,
                     summary.nominal);
  if (const std::optional<GnssNoiseModel>& noise = controls.noise) {
    batch.set_gnss_noise(noise->white_scale, noise->gauss_markov_sigma_m,
                         noise->gauss_markov_tau_s);
  }
  batch.set_track_prior(controls.track_prior);
  const bool extended = terms.has_value();
  ceres::Solver::Summary solver = extended ? solve_tyre_model(batch, options, summary, *terms)
                                           : solve_relinearised(batch, options, summary);
  const auto spread = [&] {
    if (controls.carried_spread_m) return *controls.carried_spread_m;
    std::array<double, 2> gap{};
    if (const auto& rival = controls.rival_circumference) {
      for (std::size_t w = 0; w < 2; ++w)
        gap[w] = controls.rival_share * std::abs(batch.params()[w] - (*rival)[w]);
    }
    return gap;
  };
  batch.set_model_spread(spread());
  if (controls.finish) {
    batch::FitFacts facts;
    if (solver.IsSolutionUsable()) {
      facts.usable = true;
      facts.bic = batch.information_criterion(solver);
      facts.free_tyre_coefficients = batch.free_tyre_coefficients();
      facts.wandered = batch.tyre_fit_wandered();
      facts.max_tyre_effect = max_tyre_effect(batch);
      facts.circumference = {batch.params()[0], batch.params()[1]};
      if (extended) {
        const std::array<double, 2>& gap = batch.model_spread_m();
        if (const auto u = batch.uncertainty())
          facts.circumference_variance = {u->params(0, 0) + gap[0] * gap[0],
                                          u->params(1, 1) + gap[1] * gap[1]};
      }
    }
    if (!controls.finish(facts)) return false;
  }
  adapt_doppler_noise(batch, options, summary, solver);
  adapt_gnss_noise(batch, options, common, summary, solver);
  if (extended) hold_wrong_signed_slips(batch, options, summary, solver);
  if (controls.go_on) {
    AdaptedFacts adapted{{batch.params()[0], batch.params()[1]}, std::nullopt};
    const double scale = summary.gnss_noise.covariance_scale;
    constexpr double kInfinite = std::numeric_limits<double>::infinity();
    if (!std::isfinite(scale)) {
      adapted.min_variance = {kInfinite, kInfinite};  // summarise leaves no sigma
    } else if (const auto u = batch.uncertainty()) {
      adapted.min_variance = {scale * u->params(0, 0), scale * u->params(1, 1)};
    }
    if (!controls.go_on(adapted)) return false;
  }
  batch.set_model_spread(spread());  // at the solution reported
  batch.set_forward_offset_sigma(run.forward_offset_sigma_mps2());
  batch.add_considered_uncertainty();
  summarise(run.log(), options, batch, solver, summary);
  return true;
}

batch::ModelJudgement batch::judge_model_adequacy(const CalibrationRun& run,
                                                  const OdometryParams& start,
                                                  const CalibrationOptions& common) {
  // The plain model (no tyre terms are given) with the batch's defaults (its 1 s keyframes, its
  // noises), its GNSS noise adapted as its own fit's is: under a configured sigma far above the
  // receiver's the poses follow the wheels and hide their slip (comma2k19: 3 m configured,
  // 0.13 m found).
  const BatchOptions options;
  BatchSummary scratch;
  scratch.nominal = run.log().vehicle.nominal_params();
  const BatchSummary unfitted = scratch;
  ModelJudgement judgement;
  double plain_bic = 0.0;
  std::array<double, 2> held_sigma_m{};
  {
    BatchProblem batch(run.log(), run.batch_wheels(), run.reference(), options, common, start);
    ceres::Solver::Summary solver = solve_relinearised(batch, options, scratch);
    if (solver.IsSolutionUsable()) plain_bic = batch.information_criterion(solver);
    adapt_gnss_noise(batch, options, common, scratch, solver, SigmaInflation::kSkip);
    if (!solver.IsSolutionUsable()) {
      judgement.adequacy.verdict =
          fmt::format("not judged: the batch pose graph did not solve ({})",
                      ceres::TerminationTypeToString(solver.termination_type));
      return judgement;
    }
    const double scale = scratch.gnss_noise.covariance_scale;
    const auto u = std::isfinite(scale) ? batch.uncertainty() : std::nullopt;
    if (u) {
      judgement.plain = ModelJudgement::PlainFit{
          {batch.params()[0], batch.params()[1]},
          {std::sqrt(scale * u->params(0, 0)), std::sqrt(scale * u->params(1, 1))},
          scratch.gnss_noise.adapted};
    }
    judgement.adequacy = assess_model_adequacy(batch.odometry_errors());
    batch.add_considered_uncertainty();
    const auto& track = batch.track_covariance();
    judgement.track_sigma_m = {std::sqrt(track(0, 0)), std::sqrt(track(1, 1))};
    judgement.track_width_uncertainty = options.track_width_uncertainty;
    constexpr double kInfinite = std::numeric_limits<double>::infinity();
    held_sigma_m = {u ? std::sqrt(scale * u->params(0, 0) + track(0, 0)) : kInfinite,
                    u ? std::sqrt(scale * u->params(1, 1) + track(1, 1)) : kInfinite};
  }  // freed before the tyre models' problems
  ModelAdequacy& adequacy = judgement.adequacy;
  suggest_tyre_model(adequacy);
  const TyreJudgement tyre =
      judge_against_tyre_models(run, options, common, unfitted, scratch.gnss_noise, plain_bic);
  if (const TyreCandidate* better = tyre.better_fit()) {
    const double share = tyre.gap_share();
    judgement.gap_m = {share * std::abs(start.circumference_rl_m - better->circumference[0]),
                       share * std::abs(start.circumference_rr_m - better->circumference[1])};
    judgement.gap_cannot_stand = why_it_cannot_stand(*better);
    say_a_tyre_model_fits_better(adequacy, tyre, judgement.gap_m, "this estimate's");
  }
  // Where the batch's own plain fit would put its track under its prior, so does the judge: the
  // held estimate's share is then what the track found leaves of the held one's uncertainty
  // (bench/honest_sigma.cpp: the iterative method held, 4.5 mm mean sigma, 8x the Cramér-Rao
  // sigma).
  BatchSummary held_at_start = unfitted;
  held_at_start.nominal = start;
  const HeldPlainFit held{!tyre.better_fit() || tyre.gap_share() < 1.0, adequacy.explains,
                          scratch.gnss_noise, judgement.track_sigma_m, held_sigma_m};
  judgement.track_under_prior = judge_track_under_prior(run, options, common, held_at_start, held);
  if (judgement.track_under_prior) judgement.track_sigma_m = judgement.track_under_prior->share_m;
  // Said, so that the residuals are not taken for the other method's.
  adequacy.verdict += " [judged on a batch fit of this log]";
  return judgement;
}

namespace {

// `run` prepared `log` once for both of calibrate_batch's passes; `unfitted` is the summary as it
// filled it.
BatchSummary calibrate_as_configured(const Log& log, CalibrationRun& run,
                                     const BatchOptions& options, const CalibrationOptions& common,
                                     const BatchSummary& unfitted) {
  BatchSummary summary = unfitted;
  // The Doppler fit reads the column (the reference has judged it already where it reads it too).
  if (options.doppler_sigma_mps(!run.log().gnss.speed_mps.empty()) > 0.0 &&
      !common.reference.use_gnss_speed)
    check_doppler_scale(run.log(), summary.nominal);
  bool finished = false;  // auto scores its candidates itself
  if (options.tyre_model == TyreModelChoice::kAuto) {
    finished = batch::fit_auto(run, options, common, summary);
  } else if (options.tyre_model == TyreModelChoice::kNone && common.judge_model_adequacy) {
    batch::fit_plain_judged(run, options, common, summary);
  } else {
    const std::optional<TyreTerms> terms =
        options.tyre_model == TyreModelChoice::kExtended   ? std::optional(TyreTerms::kRegression)
        : options.tyre_model == TyreModelChoice::kPhysical ? std::optional(TyreTerms::kPhysical)
                                                           : std::nullopt;
    // Chosen by hand, the regression terms carry their gap to the physical ones as under auto.
    std::optional<std::array<double, 2>> rival;
    if (terms == TyreTerms::kRegression && common.judge_model_adequacy) {
      rival = batch::physical_rival(run, options, common, unfitted,
                                    summary.tyre_selection.other_solves);
      if (rival) summary.tyre_selection.chosen_gap_to = tyre_model_option(TyreTerms::kPhysical);
    }
    batch::fit_model(run, options, common, terms, summary, {.rival_circumference = rival});
    // Chosen by hand, the physical terms are witnessed as under auto (where their answer stands).
    if (terms == TyreTerms::kPhysical && common.judge_model_adequacy) {
      int witness_solves = 0;
      batch::witness_physical_fit(run, options, common, unfitted, summary, witness_solves);
      summary.tyre_selection.other_solves += witness_solves;
    }
  }
  if (!finished) run.finish(summary);
  batch::fit_track_under_prior(run, options, common, unfitted, summary);
  batch::check_parts_consistency(log, options, common, summary);
  return summary;
}

// A stated antenna and a configured lever arm this close are one place (the yaml's rounding).
constexpr double kAntennaPlacesAgreeM = 1e-3;

// The options with the antenna where vehicle.yaml states it (gnss_x_m, gnss_y_m), which layer 1
// measures through too. A config's lever arm beside it must agree: two places for one antenna
// would have layer 1 and the batch fit different cars.
BatchOptions with_stated_antenna(BatchOptions options, const Log& log) {
  if (!log.vehicle.gnss_position_m) return options;
  const Eigen::Vector2d stated = *log.vehicle.gnss_position_m;
  const Eigen::Vector2d configured(options.lever_arm_x_m, options.lever_arm_y_m);
  if (!configured.isZero() && (configured - stated).norm() > kAntennaPlacesAgreeM) {
    throw InputError(
        {(std::filesystem::path(log.source) / "vehicle.yaml").string(), 0, "gnss_x_m"},
        fmt::format("the antenna stated at ({:+.3f}, {:+.3f}) m, but the batch's lever_arm_x_m, "
                    "lever_arm_y_m say ({:+.3f}, {:+.3f}) m: state it in one place",
                    stated.x(), stated.y(), configured.x(), configured.y()));
  }
  options.lever_arm_x_m = stated.x();
  options.lever_arm_y_m = stated.y();
  return options;
}

}  // namespace

BatchSummary calibrate_batch(const Log& log, const BatchOptions& configured,
                             const CalibrationOptions& common) {
  require_valid("batch", configured.validate());
  const BatchOptions options = with_stated_antenna(configured, log);
  BatchSummary unfitted;
  CalibrationRun run(log, common, CalibrationMethod::kBatch, unfitted);
  run.smooth_batch_heading(options.heading_tick_smoothing_s);
  const batch::Calibrate calibrate = [&](const BatchOptions& with) {
    return calibrate_as_configured(log, run, with, common, unfitted);
  };
  // Unjudged, no mounting is looked for, and its residuals are not measured (a pass over the
  // fixes per fit).
  BatchOptions first = options;
  first.detect_mounting = options.detect_mounting && common.judge_model_adequacy;
  batch::Calibrated mounted = batch::detect_mounting(calibrate, calibrate(first), first);
  batch::Calibrated result = batch::detect_latency(calibrate, std::move(mounted), first, options,
                                                   common.judge_model_adequacy);
  return batch::detect_heading_after(calibrate, std::move(result), first);
}

std::optional<Eigen::Vector2d> fitted_antenna_place(const BatchSummary& summary) {
  const EstimatedParameter* x = batch::estimated_parameter(summary, "lever_arm_x_m");
  const EstimatedParameter* y = batch::estimated_parameter(summary, "lever_arm_y_m");
  if (!x || !y || !x->identified || !y->identified) return std::nullopt;
  return Eigen::Vector2d(x->value, y->value);
}

}  // namespace odocal
