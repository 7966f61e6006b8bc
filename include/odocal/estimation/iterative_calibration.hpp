#pragma once
// The paper's iterative three-layer calibration (sections 3-4): layer 2 (an EKF of the two-wheel
// model) and layer 3 (weighted least squares for c_RL, c_RR) repeated with a decaying process
// covariance, stopping where the whole-log dead-reckoning error stops falling; and the same loop
// with a fixed covariance (the paper's "Fix RL-RR"). docs/calibration.md explains every choice
// where the paper is silent.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/estimation/calibration_options.hpp"
#include "odocal/estimation/calibration_summary.hpp"
#include "odocal/options/option_fields.hpp"

namespace odocal {

struct IterativeOptions {
  double decay_exponent_q = 2.0;                           // eq. 13b, 1 <= q <= 2
  Eigen::Vector3d fixed_process_diagonal{1.0, 1.0, 0.01};  // fixed-p: the constant P
  Eigen::Vector3d ls_weights{1.0, 1.0, 10.0};              // W, section 3.3
  int ls_window_samples = 10;  // rows of eq. 12 summed over this many samples (1: the paper)
  int max_iterations = 30;
  int patience = 5;  // stop after this many iterations without a new minimum of the score
  // Score of an iteration: mean position error [m] + this * mean heading error [rad]; the
  // paper's W equates 1 m with 0.1 rad.
  double heading_weight_m_per_rad = 10.0;
  // Above this condition number of the weighted LS rows, c_RL and c_RR cannot be separated.
  double max_condition_number = 1e6;
  // When max_iterations ends the loop while the score still falls, the estimate counts as
  // converged if its last step moved each circumference by less than this fraction of its
  // 1-sigma (the decaying covariance keeps refining by ever smaller steps).
  double step_tolerance_sigma = 0.1;

  static OptionTable<IterativeOptions> fields();
  std::string validate() const;  // empty when valid
};

struct IterationRecord {
  int iteration{};
  double circumference_rl_m{};
  double circumference_rr_m{};
  DeadReckoningSummary errors;  // whole-log dead reckoning with these parameters
  double score{};
};

struct IterativeSummary : CalibrationSummary {
  int chosen_iteration{};  // 1-based index into iterations; 0 when none finished
  std::vector<IterationRecord> iterations;

  std::string full_report() const;
};

// Throws odocal::Error for invalid options, InsufficientDataError when the log
// is too short to try (before any iteration). Every outcome after that is in the summary.
// Never reads log.truth.
IterativeSummary calibrate_iterative(const Log& log, const IterativeOptions& options = {},
                                     const CalibrationOptions& common = {});
// The same loop with the constant process covariance options.fixed_process_diagonal.
IterativeSummary calibrate_fixed_p(const Log& log, const IterativeOptions& options = {},
                                   const CalibrationOptions& common = {});

}  // namespace odocal
