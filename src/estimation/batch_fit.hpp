#pragma once
// One batch fit of the plain model or of a tyre model's family of terms, and what tyre_model
// auto compares of it: batch_calibration.cpp fits, tyre_model_selection.cpp chooses.

#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <string>

#include "calibration_run.hpp"
#include "odocal/estimation/batch_calibration.hpp"

namespace odocal::batch {

// A solved fit, taken before the GNSS noise adaptation (the information criteria are comparable
// only under one noise model).
struct FitFacts {
  bool usable = false;
  double bic = std::numeric_limits<double>::infinity();
  int free_tyre_coefficients = 0;
  double max_tyre_effect = 0.0;  // largest change of a circumference at the log's RMS state
  std::array<double, 2> circumference{};
  std::array<double, 2> circumference_variance{std::numeric_limits<double>::infinity(),
                                               std::numeric_limits<double>::infinity()};
};

using FitDecision = std::function<bool(const FitFacts&)>;

// Tyre coefficients that change the circumference by more than this at the log's typical driving
// state (RMS of each regressor) are not a tyre: they are the model explaining something else.
inline constexpr double kMaxTyreEffect = 0.03;
// Nor is a side slip of more than this at the log's RMS lateral acceleration: a rear axle past
// 6 degrees of slip angle is sliding (a car's rear tyres reach ~0.03 rad at 5 m/s^2).
inline constexpr double kMaxSideSlipRad = 0.1;

// Fits one model (the plain one, or a tyre model's family of terms); unless `finish` (when
// given) declines the solved fit, adapts its GNSS noise and fills the summary. Returns whether it
// did. The problem is freed on return.
bool fit_model(const CalibrationRun& run, const BatchOptions& options,
               const CalibrationOptions& common, std::optional<TyreTerms> terms,
               BatchSummary& summary, const FitDecision& finish = {});

// tyre_model auto (tyre_model_selection.cpp). Returns whether it has scored the result
// (run.finish) itself.
bool fit_auto(CalibrationRun& run, const BatchOptions& options, const CalibrationOptions& common,
              BatchSummary& summary);

// The report's line on that choice (empty when auto did not choose).
std::string tyre_selection_report(const BatchSummary& summary);

}  // namespace odocal::batch
