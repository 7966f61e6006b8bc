#pragma once
// Words for a parameter the batch calibration could not pin down: what about this log is
// missing, so that the user knows which drive to record.

#include <string>

#include "odocal/data/log.hpp"
#include "odocal/estimation/reference_filter.hpp"

namespace odocal {

// What the log offers for identifying each parameter.
struct LogCoverage {
  double distance_m{};
  double duration_s{};
  double left_turning_deg{};   // sum of counter-clockwise heading changes of the reference
  double right_turning_deg{};  // sum of clockwise ones
  bool has_heading{};
  bool has_gyro{};
};

LogCoverage log_coverage(const Log& log, const ReferenceTrajectory& reference);

// `name` is an EstimatedParameter name; `used` says whether any residual involved it.
std::string unidentified_reason(const std::string& name, const LogCoverage& coverage, bool used);

}  // namespace odocal
