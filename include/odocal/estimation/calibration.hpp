#pragma once
// Off-line calibration of the rear wheel circumferences (paper sections 3-5): the iterative
// three-layer method with decaying process covariance, the same loop with a fixed covariance
// ("Fix RL-RR"), and the augmented Kalman filter baseline. docs/calibration.md explains every
// choice where the paper is silent.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/estimation/batch_options.hpp"
#include "odocal/estimation/reference_filter.hpp"

namespace odocal {

enum class CalibrationMethod { kIterative, kFixedP, kAugmented, kBatch };

// Where the whole-log dead reckoning of each iteration starts (the paper is silent):
// the first reference pose; the rigid alignment (Umeyama) of the dead-reckoned path to the
// reference over the first dr_align_window_s; or over the whole log.
enum class DeadReckoningStart { kFirstReference, kAlignedWindow, kAlignedWhole };
const char* method_name(CalibrationMethod method);

struct CalibrationOptions {
  CalibrationMethod method = CalibrationMethod::kIterative;
  ReferenceOptions reference;
  Eigen::Vector3d measurement_diagonal{1.0, 1.0, 0.01};  // M, eq. 13a
  double decay_exponent_q = 2.0;                         // eq. 13b, 1 <= q <= 2 (measured default)
  Eigen::Vector3d fixed_process_diagonal{1.0, 1.0, 0.01};  // fixed-p: the constant P
  Eigen::Vector3d ls_weights{1.0, 1.0, 10.0};              // W, section 3.3
  int ls_window_samples = 10;  // rows of eq. 12 summed over this many samples (1: the paper)
  int max_iterations = 30;
  int patience = 5;  // stop after this many iterations without a new minimum of the score
  // Score of an iteration: mean position error [m] + this * mean heading error [rad]; the
  // paper's W equates 1 m with 0.1 rad.
  double heading_weight_m_per_rad = 10.0;
  DeadReckoningStart dr_start = DeadReckoningStart::kAlignedWindow;
  double dr_align_window_s = 60.0;
  // Augmented KF: pose process noise per step, parameter random walk per step, initial sigma.
  Eigen::Vector3d augmented_pose_process_diagonal{1e-4, 1e-4, 1e-6};
  double augmented_param_sigma_m_per_step = 1e-6;
  double augmented_initial_param_sigma_m = 0.02;
  BatchOptions batch;  // --method batch
  // Identifiability.
  double min_distance_m = 100.0;
  std::size_t min_reference_samples = 100;
  double max_condition_number = 1e6;
  // Below this range of the reference heading (max - min), a left/right circumference difference
  // cannot be told from a gyro or heading bias: only a common scale of the nominal
  // circumferences is estimated, and the result says so.
  double min_heading_range_for_difference_rad = 0.785;  // 45 deg

  // Empty when valid, else what is wrong.
  std::string validate() const;
};

struct DeadReckoningSummary {
  double mean_position_m{};
  double max_position_m{};
  double mean_heading_rad{};
  double max_heading_rad{};
};

struct IterationRecord {
  int iteration{};
  double circumference_rl_m{};
  double circumference_rr_m{};
  DeadReckoningSummary errors;  // whole-log dead reckoning with these parameters
  double score{};
};

// One unknown of the batch calibration besides the poses.
struct EstimatedParameter {
  std::string name;  // e.g. "circumference_rl_m", "gyro_bias_radps"
  double value{};
  double sigma{};         // 1-sigma from the covariance; infinity when it could not be computed
  bool estimated{};       // false: held at its configured value (not asked for)
  bool identified{true};  // false: this log cannot pin it down (see the verdict)
  std::string verdict;    // in words a user can act on, when not identified
};

struct CalibrationResult {
  CalibrationMethod method{};
  OdometryParams nominal;
  OdometryParams estimate;
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();  // of [c_RL, c_RR]
  double condition_number{};
  int chosen_iteration{};  // 0 for the augmented KF
  std::vector<IterationRecord> iterations;
  DeadReckoningSummary before;  // nominal parameters
  DeadReckoningSummary after;   // estimated parameters
  // Augmented KF: parameter estimates over time (the paper's Fig. 12).
  std::vector<double> parameter_t_s, parameter_c_rl_m, parameter_c_rr_m;
  std::size_t reference_samples{};
  std::string reference_heading_source;
  double distance_m{};
  std::string termination;              // why it stopped, in words
  bool difference_identifiable = true;  // false: c_RL / c_RR kept at the nominal ratio
  std::string identifiability;          // in words, for the user
  // Batch: every unknown besides the poses, and the solver's report.
  std::vector<EstimatedParameter> parameters;
  std::string solver_report;
};

// Throws InsufficientDataError when the log cannot identify the circumferences, and Error for
// invalid options. Never reads log.truth.
CalibrationResult calibrate(const Log& log, const CalibrationOptions& options = {});

}  // namespace odocal
