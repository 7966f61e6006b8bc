#pragma once
// The paper's baseline (section 5): an augmented Kalman filter with state
// [x, y, yaw, c_RL, c_RR], predicted by the two-wheel model and corrected by the layer-1
// reference pose; its estimate is the final state.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/estimation/calibration_options.hpp"
#include "odocal/estimation/calibration_summary.hpp"
#include "odocal/options/option_fields.hpp"

namespace odocal {

struct AugmentedOptions {
  // Pose process noise per step [x m^2, y m^2, yaw rad^2].
  Eigen::Vector3d pose_process_diagonal{1e-4, 1e-4, 1e-6};
  double param_sigma_m_per_step = 1e-6;  // random walk of each circumference
  double initial_param_sigma_m = 0.02;

  static OptionTable<AugmentedOptions> fields();
  std::string validate() const;  // empty when valid
};

struct AugmentedSummary : CalibrationSummary {
  // The parameter estimates over time (the paper's Fig. 12), one per reference sample after the
  // first.
  std::vector<double> parameter_t_s, parameter_c_rl_m, parameter_c_rr_m;

  std::string full_report() const;
};

// Throws for invalid options and for a log too short to try; every other outcome is in the
// summary. Never reads log.truth.
AugmentedSummary calibrate_augmented(const Log& log, const AugmentedOptions& options = {},
                                     const CalibrationOptions& common = {});

}  // namespace odocal
