#pragma once
// What every calibration method does around its own estimator: computes the layer-1 reference,
// refuses a log too short to try (InsufficientDataError, before any estimate), decides whether
// the left/right difference is identifiable, scores the nominal parameters, and at the end
// scores the estimate and refuses numbers that make no physical sense.

#include <optional>

#include "odocal/data/fitted_wheels.hpp"
#include "odocal/data/log.hpp"
#include "odocal/estimation/calibration_options.hpp"
#include "odocal/estimation/calibration_summary.hpp"
#include "odocal/estimation/reference_filter.hpp"
#include "whole_log_evaluator.hpp"

namespace odocal {

class CalibrationRun {
 public:
  // Validates `options`, then fills the summary's method, nominal (and estimate = nominal),
  // reference facts, motion coverage and distance, identifiability and `before`. Keeps
  // references to `log` and `options`.
  CalibrationRun(const Log& log, const CalibrationOptions& options, CalibrationMethod method,
                 CalibrationSummary& summary);
  CalibrationRun(const CalibrationRun&) = delete;
  CalibrationRun& operator=(const CalibrationRun&) = delete;

  // The log the estimators use: the input, with the odometry chain broken at wheel gaps.
  const Log& log() const { return prepared_ ? *prepared_ : log_; }
  // The wheels the batch's pose graph fits: log()'s with the rear wheels' tick difference
  // averaged over +-heading_tick_smoothing_s (BatchOptions), as set by smooth_batch_heading;
  // log()'s own before that or with 0. Only the change of each sample's difference is kept
  // beside the log (a copy of the wheels was 79 MiB on a 10-hour drive); dead reckoning and
  // everything else read log().
  FittedWheels batch_wheels() const { return {log().wheels, batch_heading_change_}; }
  void smooth_batch_heading(double heading_tick_smoothing_s);
  const ReferenceTrajectory& reference() const { return reference_; }
  WholeLogEvaluator& evaluator() { return evaluator_; }
  // What is left of imu.csv's forward offset after preparing, 1 sigma, m/s^2 (0 without imu.csv):
  // the physical tyre terms take the forward reading for drive force.
  double forward_offset_sigma_mps2() const { return forward_offset_sigma_mps2_; }

  // Scores the estimate (`after`; with a non-finite estimate `after` stays `before`) and turns
  // a converged result that makes no physical sense into Termination::kImplausible: not finite,
  // further than max_relative_change from nominal, or dead-reckoning worse than nominal.
  void finish(CalibrationSummary& summary);
  // The whole log dead-reckoned with the summary's estimate and tyre model (what finish() puts
  // in `after`), for comparing two fits before either is finished; `before` where the estimate is
  // not finite.
  DeadReckoningSummary dead_reckon(const CalibrationSummary& summary);

 private:
  // What finish() adds to dead_reckon(): the heading walk that the accelerometer's noise makes in
  // that dead reckoning, from the same driving states.
  void dead_reckon_with_walk(CalibrationSummary& summary);

  const Log& log_;
  const CalibrationOptions& options_;
  std::optional<Log> prepared_;               // only when preparing changed something
  std::vector<double> batch_heading_change_;  // empty: none
  ReferenceTrajectory reference_;
  WholeLogEvaluator evaluator_;
  double forward_offset_sigma_mps2_{};
};

// Mean position error plus the paper's 10 m/rad of mean heading error: lower dead-reckons better.
double dead_reckoning_score(const DeadReckoningSummary& summary);

// Turns a summary whose estimate makes no physical sense into Termination::kImplausible, with
// the likely input mistake in its message (called by finish()).
void check_plausibility(const Log& log, const CalibrationOptions& options,
                        CalibrationSummary& summary);

// Throws odocal::Error naming the options' kind when `problem` (a validate() result) is not
// empty.
void require_valid(const char* kind, const std::string& problem);

}  // namespace odocal
