#pragma once
// Words for a parameter the batch calibration could not pin down: what about this log is
// missing, so that the user knows which drive to record.

#include <string>

#include "odocal/data/log.hpp"
#include "odocal/estimation/motion_coverage.hpp"

namespace odocal {

// What the log offers for identifying each parameter.
struct LogCoverage {
  double distance_m{};        // while moving
  double duration_s{};        // moving
  double left_turning_deg{};  // while moving (motion_coverage.hpp)
  double right_turning_deg{};
  bool has_heading{};
  bool has_gyro{};
};

LogCoverage log_coverage(const Log& log, const MotionCoverage& motion);

// `name` is an EstimatedParameter name; `used` says whether any residual involved it.
std::string unidentified_reason(const std::string& name, const LogCoverage& coverage, bool used);

}  // namespace odocal
