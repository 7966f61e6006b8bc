#pragma once
// Held-out validation: what a calibration buys when GNSS is lost. The log is cut into windows;
// each is dead-reckoned from the reference pose at its start, as if GNSS had gone there, and its
// drift is the distance from the reference pose at the window's end, in metres and in % of the
// distance driven in the window. Compared for two parameter sets (nominal and calibrated).
// Where the reference carries its covariance, each window also gets the end error that the
// reference's own uncertainty makes: a drift near it measures the reference, not the parameters.

#include <optional>
#include <string>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/estimation/reference_filter.hpp"
#include "odocal/estimation/tick_dequantisation.hpp"

namespace odocal {

struct DriftValidationOptions {
  double window_s = 60.0;
  double min_window_distance_m = 20.0;  // shorter windows (standing, creeping) are skipped
  // A window starts every step_s seconds; 0: every window_s (disjoint windows). Overlapping
  // windows give more, correlated windows: steadier medians on a short log.
  double step_s = 0.0;
  // Tick counts are averaged over +-this before dead reckoning (tick_dequantisation.hpp); 0: the
  // counts as they are, as a controller that integrates them raw would see them.
  double tick_smoothing_s = kDefaultTickSmoothingS;
  std::string validate() const;  // empty when valid
};

struct WindowDrift {
  double start_s{};
  double distance_m{};
  double end_error_m{};
  double drift_percent{};  // end error / distance * 100
};

struct DriftStatistics {
  std::size_t windows{};
  double median_end_error_m{};
  double p95_end_error_m{};
  double median_drift_percent{};
  double p95_drift_percent{};
};

// The end error of a window that the reference alone makes, its start pose (position and heading,
// the heading turning the whole window's displacement) and its end position taken as independent
// (the smoother's errors decorrelate within seconds; a window lasts a minute). Per window the RMS
// of that Gaussian; over the windows the medians of the end error and the drift that these
// Gaussians alone would show, to set beside DriftStatistics' measured ones.
struct ReferenceUncertainty {
  std::vector<double> rms_m;  // per window, as DriftValidation::nominal
  double median_end_error_m{};
  double median_drift_percent{};  // over the nominal windows' distances
};

struct DriftValidation {
  std::vector<WindowDrift> nominal;     // one per usable window
  std::vector<WindowDrift> calibrated;  // the same windows
  DriftStatistics nominal_statistics;
  DriftStatistics calibrated_statistics;
  std::optional<ReferenceUncertainty> reference;  // with the reference's covariance only
  std::size_t windows_with_gaps{};                // left out: a wheel gap inside (wheel_gaps.hpp)
};

// Throws InsufficientDataError when no window is long enough, Error for invalid options.
DriftValidation validate_drift(const WheelStream& wheels, const ReferenceTrajectory& reference,
                               const OdometryParams& nominal, const OdometryParams& calibrated,
                               const DriftValidationOptions& options = {});

// The same where each parameter set dead-reckons its own increments of the same samples (a tyre
// model applied: driving_state.hpp's with_tyre_model).
DriftValidation validate_drift(const WheelStream& nominal_wheels,
                               const WheelStream& calibrated_wheels,
                               const ReferenceTrajectory& reference, const OdometryParams& nominal,
                               const OdometryParams& calibrated,
                               const DriftValidationOptions& options = {});

// The antenna where a calibration found it is the validation's too (its reference measures the
// axle through it), unless vehicle.yaml states one. True when `vehicle` took `found_m`.
bool adopt_found_antenna(VehicleConfig& vehicle, const std::optional<Eigen::Vector2d>& found_m);

}  // namespace odocal
