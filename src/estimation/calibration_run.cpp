#include "calibration_run.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "batch_fit.hpp"
#include "input_mistake_hint.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/accelerometer_offset.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/estimation/tick_dequantisation.hpp"
#include "odocal/model/angle.hpp"

namespace odocal {
namespace {

ReferenceTrajectory checked_reference(const Log& log, const CalibrationOptions& options) {
  require_valid("calibration", options.validate());
  ReferenceTrajectory reference = compute_reference(log, options.reference);
  if (reference.poses.size() < options.min_reference_samples) {
    throw InsufficientDataError(
        fmt::format("too short: the reference covers {} wheel samples, at least {} are needed",
                    reference.poses.size(), options.min_reference_samples));
  }
  return reference;
}

void decide_difference_identifiability(const CalibrationOptions& options,
                                       CalibrationSummary& summary) {
  const MotionCoverage& c = summary.coverage;
  summary.difference_identifiable = c.turning_rad() >= options.min_turning_for_difference_rad;
  const std::string turned =
      fmt::format("{:.0f} deg of turning while moving (left {:.0f}, right {:.0f}, from the {})",
                  deg_from_rad(c.turning_rad()), deg_from_rad(c.left_turning_rad),
                  deg_from_rad(c.right_turning_rad), c.turning_source);
  summary.identifiability =
      summary.difference_identifiable
          ? fmt::format("c_RL and c_RR identified separately ({})", turned)
          : fmt::format(
                "the left/right difference is not identifiable: {}, needs {:.0f} deg to tell it "
                "from a gyro or heading bias; only the common scale of the nominal circumferences "
                "was estimated",
                turned, deg_from_rad(options.min_turning_for_difference_rad));
}

// The squared Mahalanobis distance of the nominal circumferences from the estimate under its
// covariance; infinite when the estimate changed more than the circumferences (track width, tyre
// model) or moved along a direction its covariance says it cannot (a rank-deficient covariance:
// the ratio kept at nominal).
double nominal_distance_squared(const CalibrationSummary& s) {
  if (s.estimate.track_width_m != s.nominal.track_width_m || !s.tyre_model.plain())
    return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d difference(s.nominal.circumference_rl_m - s.estimate.circumference_rl_m,
                                   s.nominal.circumference_rr_m - s.estimate.circumference_rr_m);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(s.covariance);
  const double largest = eigen.eigenvalues().maxCoeff();
  if (!(largest > 0.0)) return std::numeric_limits<double>::infinity();
  double distance = 0.0;
  for (int i = 0; i < 2; ++i) {
    const double along = eigen.eigenvectors().col(i).dot(difference);
    const double variance = eigen.eigenvalues()(i);
    if (variance > 1e-12 * largest) {
      distance += along * along / variance;
    } else if (std::abs(along) > 1e-9) {  // a nanometre: further than the estimate can move
      return std::numeric_limits<double>::infinity();
    }
  }
  return distance;
}

// These methods have no sigma threshold of their own: an estimate that a better-fitting tyre
// model puts beyond 3 of its own sigma from the circumference at rest is contradicted at its own
// precision, and is not a result to export, however wide its sigma is made.
void refuse_a_gap_beyond_the_estimates_own_sigma(const std::array<double, 2>& gap_m,
                                                 const std::array<double, 2>& own_sigma_m,
                                                 const std::string& gap_cannot_stand,
                                                 CalibrationSummary& summary) {
  constexpr double kSigmas = 3.0;
  if (!(gap_m[0] > kSigmas * own_sigma_m[0] || gap_m[1] > kSigmas * own_sigma_m[1])) return;
  summary.termination = Termination::kNotIdentifiable;
  summary.message = fmt::format(
      "the two-wheel model does not explain this log: a tyre model that fits it better puts the "
      "circumferences at rest {:.3g} / {:.3g} mm from this estimate, {:.1f} / {:.1f} times its own "
      "1-sigma (this estimate is the circumference the drive rolled on, slip and load in it); "
      "{}",
      1e3 * gap_m[0], 1e3 * gap_m[1], gap_m[0] / own_sigma_m[0], gap_m[1] / own_sigma_m[1],
      gap_cannot_stand.empty()
          ? "calibrate with --method batch, whose tyre_model: auto fits the circumference at rest"
          : "but that model " + gap_cannot_stand);
}

// The batch's plain fit of the same log is at the Cramér-Rao bound, so this estimate's variance
// is at least the batch's plus that of their difference (Hausman: the efficient estimate is
// uncorrelated with an inefficient one's departure from it), whose one sample is the gap between
// the two. Where the judge's residuals showed that the configured GNSS noise is wrong, this
// estimate's sigma rests on the wrong noise too: the ideal circuit under a 2 m Gauss-Markov error
// over 120 s configured as 0.1 m white (odocal_honest_sigma's run 12): the iterative method
// +1.56 mm at sigma 0.41 mm; over 60 s (run 33): +2.65 mm at the batch's sigma 0.80 mm, 0.50 mm
// from it. Where the noise is the configured one, a gap beyond 3 of this estimate's own sigma is
// a bias, not chance (the gap's variance is this estimate's less the batch's): the layer-1
// reference is off. tools/independent_drive.py's 10 km with 3 m fixes and no heading.csv, the
// iterative method on the filter's reference: -1.9 to -17.7 mm at sigma 2.5-3.4 mm (seeds 1-6;
// the smoother's reference -0.1 mm, the batch's 0.0 mm at seed 4).
void claim_no_less_than_the_plain_batch(const batch::ModelJudgement::PlainFit& batch,
                                        bool smoothed_reference, CalibrationSummary& summary) {
  const std::array<double, 2> estimate{summary.estimate.circumference_rl_m,
                                       summary.estimate.circumference_rr_m};
  const std::array<double, 2> own_sigma_m{summary.sigma_rl_m(), summary.sigma_rr_m()};
  std::array<double, 2> gap_m{};
  bool raised = false;
  for (int w = 0; w < 2; ++w) {
    const auto i = static_cast<std::size_t>(w);
    gap_m[i] = estimate[i] - batch.circumference_m[i];
    const double floor = batch.sigma_m[i] * batch.sigma_m[i] + gap_m[i] * gap_m[i];
    const double variance = summary.covariance(w, w);
    if (!(variance < floor)) continue;
    raised = true;
    if (variance > 0.0) {
      const double scale = std::sqrt(floor / variance);  // the correlation kept
      summary.covariance.row(w) *= scale;
      summary.covariance.col(w) *= scale;
    } else {
      summary.covariance(w, w) = floor;
    }
  }
  if (!raised) return;
  summary.model_adequacy.verdict += fmt::format(
      "; {}this estimate's sigma is at least the batch's{}, {:.3g} / {:.3g} mm, with this "
      "estimate's gap to the batch's, {:+.3g} / {:+.3g} mm",
      batch.noise_adapted ? "the GNSS noise is not the configured one (the batch's residuals "
                            "show it): "
                          : "",
      batch.noise_adapted ? " under the noise they show" : "", 1e3 * batch.sigma_m[0],
      1e3 * batch.sigma_m[1], 1e3 * gap_m[0], 1e3 * gap_m[1]);
  constexpr double kSigmas = 3.0;
  if (batch.noise_adapted || !summary.usable() ||
      !(std::abs(gap_m[0]) > kSigmas * own_sigma_m[0] ||
        std::abs(gap_m[1]) > kSigmas * own_sigma_m[1]))
    return;
  summary.termination = Termination::kNotIdentifiable;
  summary.message = fmt::format(
      "this estimate is {:+.3g} / {:+.3g} mm from the batch's fit of the same model to the same "
      "log, {:.1f} / {:.1f} times its own 1-sigma: its layer-1 reference is off{}",
      1e3 * gap_m[0], 1e3 * gap_m[1], std::abs(gap_m[0]) / own_sigma_m[0],
      std::abs(gap_m[1]) / own_sigma_m[1],
      smoothed_reference ? "; calibrate with --method batch"
                         : " (a filter lags through the turns where the log has no heading.csv "
                           "and coarse fixes); calibrate with --reference smoother, or with "
                           "--method batch");
}

// Whether the circumferences and track are numbers (not a diverged fit's).
bool finite_geometry(const OdometryParams& e) {
  return std::isfinite(e.circumference_rl_m) && std::isfinite(e.circumference_rr_m) &&
         std::isfinite(e.track_width_m);
}

// Whether dead reckoning can take the fit: its tyre coefficients too.
bool finite_fit(const CalibrationSummary& summary) {
  return finite_geometry(summary.estimate) && summary.tyre_model.coefficients().allFinite();
}

}  // namespace

double dead_reckoning_score(const DeadReckoningSummary& s) {
  return s.mean_position_m + 10.0 * s.mean_heading_rad;
}

void check_plausibility(const Log& log, const CalibrationOptions& options,
                        CalibrationSummary& summary) {
  const OdometryParams& e = summary.estimate;
  const OdometryParams& n = summary.nominal;
  const bool finite = std::isfinite(e.circumference_rl_m) && std::isfinite(e.circumference_rr_m) &&
                      std::isfinite(e.track_width_m) && summary.covariance.allFinite();
  if (!finite) {
    summary.termination = Termination::kImplausible;
    summary.message =
        fmt::format("the estimate or its covariance is not a finite number (c_RL {}, c_RR {}): {}",
                    e.circumference_rl_m, e.circumference_rr_m, likely_input_mistake(-1.0, log));
    return;
  }
  const double change_rl = e.circumference_rl_m / n.circumference_rl_m - 1.0;
  const double change_rr = e.circumference_rr_m / n.circumference_rr_m - 1.0;
  if (std::max(std::abs(change_rl), std::abs(change_rr)) > options.max_relative_change) {
    const double ratio = 0.5 * (e.circumference_rl_m / n.circumference_rl_m +
                                e.circumference_rr_m / n.circumference_rr_m);
    summary.termination = Termination::kImplausible;
    summary.message = fmt::format(
        "c_RL {:.6f} m and c_RR {:.6f} m are {:+.1f} % and {:+.1f} % from the nominal "
        "circumferences, more than max_relative_change ({:.0f} %): {}",
        e.circumference_rl_m, e.circumference_rr_m, 100.0 * change_rl, 100.0 * change_rr,
        100.0 * options.max_relative_change, likely_input_mistake(ratio, log));
    return;
  }
  const double before = dead_reckoning_score(summary.before);
  const double after = dead_reckoning_score(summary.after);
  constexpr double kNoiseFloorM = 0.5;
  if (after <= before * (1.0 + options.max_dead_reckoning_increase) + kNoiseFloorM) return;
  // Worse dead reckoning is no sign of a mistake when the nominal circumferences are inside the
  // estimate's 3-sigma region: the log cannot tell them apart, and over a long drive a fraction
  // of a millimetre is metres.
  constexpr double kChi2TwoDof3Sigma = 11.83;
  const double distance2 = nominal_distance_squared(summary);
  if (distance2 <= kChi2TwoDof3Sigma) {
    summary.note = fmt::format(
        "the nominal circumferences are inside this estimate's 3-sigma region (Mahalanobis "
        "distance {:.1f}), and they dead-reckon the log better (mean position error {:.2f} m "
        "against {:.2f} m): the log cannot tell them apart; keep the nominal ones",
        std::sqrt(distance2), summary.before.mean_position_m, summary.after.mean_position_m);
    return;
  }
  summary.termination = Termination::kImplausible;
  summary.message = fmt::format(
      "the estimate dead-reckons the log worse than the nominal parameters (mean position error "
      "{:.2f} m -> {:.2f} m, mean heading error {:.2f} -> {:.2f} deg): the model does not fit "
      "this log; look for gaps, a clock offset between wheels and GNSS, or wrong signs",
      summary.before.mean_position_m, summary.after.mean_position_m,
      deg_from_rad(summary.before.mean_heading_rad), deg_from_rad(summary.after.mean_heading_rad));
}

void require_valid(const char* kind, const std::string& problem) {
  if (!problem.empty()) throw Error(fmt::format("invalid {} options: {}", kind, problem));
}

CalibrationRun::CalibrationRun(const Log& log, const CalibrationOptions& options,
                               CalibrationMethod method, CalibrationSummary& summary)
    : log_(log),
      options_(options),
      prepared_(prepare_log(log, options, summary.preparation)),
      reference_(checked_reference(this->log(), options)),
      evaluator_(this->log().wheels, reference_, options) {
  summary.method = method;
  if (this->log().imu) {
    // Measured at 3 stops or more, else over the drive where it can tell the slope; otherwise the
    // unmeasured sigma, no narrower than what the accelerometer reads beyond the wheels while
    // driving straight.
    const LogPreparation& prepared = summary.preparation;
    const auto& offset = prepared.accelerometer_offset;
    if (offset && offset->stops >= kMinStopsForOffset) {
      forward_offset_sigma_mps2_ = offset->left_sigma_mps2();
    } else if (prepared.drive_forward_offset) {
      forward_offset_sigma_mps2_ = prepared.drive_forward_offset->left_sigma_mps2();
    } else {
      forward_offset_sigma_mps2_ = kUnmeasuredForwardOffsetSigmaMps2;
      const auto driving = driving_forward_offset(this->log(), log.vehicle.nominal_params());
      summary.preparation.driving_forward_offset_mps2 = driving;
      if (driving)
        forward_offset_sigma_mps2_ = std::max(forward_offset_sigma_mps2_, std::abs(*driving));
    }
  }
  summary.nominal = log.vehicle.nominal_params();
  summary.estimate = summary.nominal;
  summary.reference_samples = reference_.poses.size();
  summary.reference_heading_source = reference_.heading_source;
  const std::span<const double> t = reference_.times(this->log().wheels);
  summary.coverage =
      motion_coverage(this->log(), summary.nominal, t.front(), t.back(), options.coverage);
  summary.distance_m = summary.coverage.distance_m;
  if (summary.distance_m < options.min_distance_m) {
    throw InsufficientDataError(fmt::format(
        "the vehicle barely moves: {:.1f} m of wheel odometry while moving, at least {} m are "
        "needed",
        summary.distance_m, options.min_distance_m));
  }
  decide_difference_identifiability(options, summary);
  // The nominal vehicle as vehicle.yaml states it, with its tyre model where it has one.
  const TyreModel nominal_tyre = log.vehicle.tyre_model.value_or(TyreModel{});
  summary.before =
      nominal_tyre.plain()
          ? evaluator_.evaluate(summary.nominal)
          : evaluator_.evaluate(summary.nominal,
                                with_tyre_model(this->log(), summary.nominal, nominal_tyre));
}

DeadReckoningSummary CalibrationRun::dead_reckon(const CalibrationSummary& summary) {
  const OdometryParams& e = summary.estimate;
  if (!finite_fit(summary)) return summary.before;
  if (summary.tyre_model.plain()) return evaluator_.evaluate(e);
  return evaluator_.evaluate(e, with_tyre_model(log(), e, summary.tyre_model));
}

void CalibrationRun::dead_reckon_with_walk(CalibrationSummary& summary) {
  const Log& prepared = log();
  const TyreModel& model = summary.tyre_model;
  if (model.plain() || !prepared.imu || !finite_fit(summary)) {
    summary.after = dead_reckon(summary);
    return;
  }
  // The states as with_tyre_model(log, ...) counts them, computed once for both.
  const OdometryParams& e = summary.estimate;
  const VehicleBody body = prepared.vehicle.body_geometry();
  const std::vector<DrivingState> states =
      driving_states(prepared.wheels, &*prepared.imu, e, driving_states(prepared, e), model, body);
  summary.after = evaluator_.evaluate(e, with_tyre_model(prepared.wheels, states, model, body));
  summary.accelerometer_walk =
      accelerometer_heading_walk(prepared.wheels, *prepared.imu, states, model, body, e);
}

void CalibrationRun::smooth_batch_heading(double heading_tick_smoothing_s) {
  batch_heading_change_ = heading_tick_change(log().wheels, heading_tick_smoothing_s);
}

void CalibrationRun::finish(CalibrationSummary& summary) {
  const OdometryParams& e = summary.estimate;
  dead_reckon_with_walk(summary);
  // The hills' projection is uncertain by the noise of the fitted grades: a common scale.
  if (summary.preparation.grade_scale_variance > 0.0 && finite_geometry(e)) {
    const Eigen::Vector2d c(e.circumference_rl_m, e.circumference_rr_m);
    summary.covariance += summary.preparation.grade_scale_variance * c * c.transpose();
  }
  if (summary.termination == Termination::kConverged) check_plausibility(log(), options_, summary);
  // The batch judges its own fit (batch_calibration.cpp).
  if (summary.method != CalibrationMethod::kBatch && summary.usable() &&
      options_.judge_model_adequacy) {
    std::array<double, 2> gap_m{};
    std::string gap_cannot_stand;
    std::optional<batch::ModelJudgement::PlainFit> plain;
    try {
      smooth_batch_heading(BatchOptions{}.heading_tick_smoothing_s);  // the batch's default
      const batch::ModelJudgement judged = batch::judge_model_adequacy(*this, e, options_);
      summary.model_adequacy = judged.adequacy;
      gap_m = judged.gap_m;
      gap_cannot_stand = judged.gap_cannot_stand;
      plain = judged.plain;
      summary.track_sigma_m = judged.track_sigma_m;
      if (const auto& track = judged.track_under_prior) {
        summary.judged_track_m = track->track_m;
        summary.judged_track_sigma_m = track->sigma_m;
      }
      summary.track_width_uncertainty = judged.track_width_uncertainty;
    } catch (const InsufficientDataError& error) {
      summary.model_adequacy.verdict = fmt::format("not judged: {}", error.what());
    }
    // The judge fitted the same two-wheel model to the same log: where its residuals are wider
    // than their noise, so is this estimate's uncertainty (3 laps of Hockenheim's racing line,
    // rear-driven: the iterative method -40.8 mm at sigma 1.5 mm, the judge's chi2/dof 592).
    summary.misfit_sigma_scale = misfit_sigma_scale(summary.model_adequacy);
    summary.covariance *= summary.misfit_sigma_scale * summary.misfit_sigma_scale;
    if (plain) {
      const bool smoothed = options_.reference.mode == ReferenceMode::kSmoother;
      claim_no_less_than_the_plain_batch(*plain, smoothed, summary);
    }
    // Where a tyre model fits the log better, this estimate is the circumference the drive
    // rolled on, and the one at rest lies as far away as that model's (the built-in circuit,
    // realistic, rear-driven: the iterative method -29 mm at sigma 1.2 mm).
    const std::array<double, 2> own_sigma_m{summary.sigma_rl_m(), summary.sigma_rr_m()};
    // Held, the track is as uncertain here as in the plain batch, whose turns set the scale
    // through it (docs/batch-calibration.md, "The track the wheels roll on"), or as far as the
    // judge's track under its prior leaves it ("The track under its prior"). Not in the sigma
    // that the gap is weighed against: a tyre model carries the load that moves the track.
    for (int w = 0; w < 2; ++w) {
      const auto i = static_cast<std::size_t>(w);
      const double track_m = summary.track_sigma_m[i];
      summary.covariance(w, w) += gap_m[i] * gap_m[i] + track_m * track_m;
    }
    refuse_a_gap_beyond_the_estimates_own_sigma(gap_m, own_sigma_m, gap_cannot_stand, summary);
  }
}

}  // namespace odocal
