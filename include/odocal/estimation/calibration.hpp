#pragma once
// One front door for the command line and the config file: a CalibrationConfig names the
// method and holds every method's options (the `odocal calibrate --config` file), and
// calibrate() runs the chosen one. Library users who know their method call it directly
// (calibrate_iterative, calibrate_fixed_p, calibrate_augmented, calibrate_batch).

#include <string>
#include <variant>

#include "odocal/estimation/augmented_calibration.hpp"
#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/estimation/iterative_calibration.hpp"

namespace odocal {

struct CalibrationConfig {
  CalibrationMethod method = CalibrationMethod::kIterative;
  CalibrationOptions common;
  IterativeOptions iterative;  // iterative and fixed-p
  AugmentedOptions augmented;
  BatchOptions batch;

  static OptionTable<CalibrationConfig> fields();  // `method`; the sections have their own
  std::string validate() const;                    // empty when valid; every section
};

// The layout of the `--config` file: which table's fields sit in which section ("" is the top
// level, else the key of a nested mapping), with a title for --print-config. Every reader and
// writer of the file walks this, so the layout is written once. `Config` is CalibrationConfig or
// const CalibrationConfig; `visit(section, title, table, object)`.
template <typename Config, typename Visit>
void for_each_config_section(Config& config, Visit&& visit) {
  visit("", "which estimator runs", CalibrationConfig::fields(), config);
  visit("", "every method", CalibrationOptions::fields(), config.common);
  visit("reference", "layer 1: the GNSS/IMU reference (every method)", ReferenceOptions::fields(),
        config.common.reference);
  visit("coverage", "what counts as moving and turning (every method)",
        MotionCoverageOptions::fields(), config.common.coverage);
  visit("standstill", "what counts as standing still (every method)", StandstillOptions::fields(),
        config.common.standstill);
  visit("", "iterative and fixed-p", IterativeOptions::fields(), config.iterative);
  visit("augmented", "the augmented Kalman filter", AugmentedOptions::fields(), config.augmented);
  visit("batch", "the batch maximum-likelihood estimator", BatchOptions::fields(), config.batch);
}

// The summary of whichever method ran.
using AnyCalibrationSummary = std::variant<IterativeSummary, AugmentedSummary, BatchSummary>;

AnyCalibrationSummary calibrate(const Log& log, const CalibrationConfig& config = {});

const CalibrationSummary& core(const AnyCalibrationSummary& summary);
std::string full_report(const AnyCalibrationSummary& summary);

}  // namespace odocal
