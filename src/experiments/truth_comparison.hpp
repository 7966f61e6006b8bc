#pragma once
// A calibration judged against the simulator's truth, and the accuracy limit of the same log.

#include <nlohmann/json.hpp>

#include "odocal/estimation/calibration.hpp"
#include "odocal/estimation/cramer_rao.hpp"
#include "odocal/estimation/trajectory_errors.hpp"
#include "odocal/sim/scenario.hpp"

namespace odocal::experiments {

struct TruthComparison {
  double error_rl_mm{};  // estimate - truth
  double error_rr_mm{};
  double reported_sigma_rl_mm{};  // the method's own 1-sigma (its covariance)
  double reported_sigma_rr_mm{};
  // Whole-log dead reckoning with the estimate (and its tyre model) from the true start pose,
  // against the truth.
  TrajectoryErrors dead_reckoning;
};

// `log` must carry its truth; `truth` are the true parameters.
TruthComparison compare_with_truth(const CalibrationSummary& result, const Log& log,
                                   const OdometryParams& truth);

// The bound for the scenario's GNSS (white and Gauss-Markov; outliers left out) and heading
// noise, along the true start and parameters, with
// the log's encoder quantisation as count noise (or, for comparison, the counts taken as exact).
enum class CountModel { kQuantised, kExact };
CramerRaoBound scenario_cramer_rao_bound(const sim::Scenario& scenario, const Log& log,
                                         const OdometryParams& truth,
                                         CountModel counts = CountModel::kQuantised);

// One calibration, timed and judged.
struct MethodRun {
  AnyCalibrationSummary result;
  TruthComparison comparison;
  double milliseconds{};
};
MethodRun run_method(const Log& log, const OdometryParams& truth, const CalibrationConfig& options);

nlohmann::json method_run_to_json(const MethodRun& run);

}  // namespace odocal::experiments
