#pragma once
// What every calibration method does around its own estimator: computes the layer-1 reference,
// refuses a log too short to try (InsufficientDataError, before any estimate), decides whether
// the left/right difference is identifiable, scores the nominal parameters, and at the end
// scores the estimate and refuses numbers that make no physical sense.

#include "odocal/data/log.hpp"
#include "odocal/estimation/calibration_options.hpp"
#include "odocal/estimation/calibration_summary.hpp"
#include "odocal/estimation/reference_filter.hpp"
#include "whole_log_evaluator.hpp"

namespace odocal {

class CalibrationRun {
 public:
  // Validates `options`, then fills the summary's method, nominal (and estimate = nominal),
  // reference facts, distance, identifiability and `before`.
  CalibrationRun(const Log& log, const CalibrationOptions& options, CalibrationMethod method,
                 CalibrationSummary& summary);
  CalibrationRun(const CalibrationRun&) = delete;
  CalibrationRun& operator=(const CalibrationRun&) = delete;

  const ReferenceTrajectory& reference() const { return reference_; }
  WholeLogEvaluator& evaluator() { return evaluator_; }

  // Scores the estimate (`after`; with a non-finite estimate `after` stays `before`) and turns
  // a converged result with a non-finite estimate or covariance into Termination::kImplausible.
  void finish(CalibrationSummary& summary);

 private:
  ReferenceTrajectory reference_;
  WholeLogEvaluator evaluator_;
};

// Throws odocal::Error naming the options' kind when `problem` (a validate() result) is not
// empty.
void require_valid(const char* kind, const std::string& problem);

}  // namespace odocal
