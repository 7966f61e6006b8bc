#include "calibration_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "odocal/error.hpp"
#include "odocal/model/angle.hpp"

namespace odocal {
namespace {

ReferenceTrajectory checked_reference(const Log& log, const CalibrationOptions& options) {
  require_valid("calibration", options.validate());
  ReferenceTrajectory reference = compute_reference(log, options.reference);
  if (reference.poses.size() < options.min_reference_samples) {
    throw InsufficientDataError(
        fmt::format("too short: the reference covers {} wheel samples, at least {} are needed",
                    reference.poses.size(), options.min_reference_samples));
  }
  return reference;
}

void decide_difference_identifiability(const ReferenceTrajectory& reference,
                                       const CalibrationOptions& options,
                                       CalibrationSummary& summary) {
  double lowest = reference.poses.pose[0].z(), highest = lowest;
  for (const Pose2& pose : reference.poses.pose) {
    lowest = std::min(lowest, pose.z());
    highest = std::max(highest, pose.z());
  }
  summary.difference_identifiable =
      highest - lowest >= options.min_heading_range_for_difference_rad;
  summary.identifiability =
      summary.difference_identifiable
          ? fmt::format("c_RL and c_RR identified separately (heading range {:.0f} deg)",
                        deg_from_rad(highest - lowest))
          : fmt::format(
                "the left/right difference is not identifiable: the heading only spans {:.1f} deg "
                "(needs {:.0f} deg of turning to tell it from a gyro or heading bias); only the "
                "common scale of the nominal circumferences was estimated",
                deg_from_rad(highest - lowest),
                deg_from_rad(options.min_heading_range_for_difference_rad));
}

}  // namespace

void require_valid(const char* kind, const std::string& problem) {
  if (!problem.empty()) throw Error(fmt::format("invalid {} options: {}", kind, problem));
}

CalibrationRun::CalibrationRun(const Log& log, const CalibrationOptions& options,
                               CalibrationMethod method, CalibrationSummary& summary)
    : reference_(checked_reference(log, options)), evaluator_(log.wheels, reference_, options) {
  summary.method = method;
  summary.nominal = log.vehicle.nominal_params();
  summary.estimate = summary.nominal;
  summary.reference_samples = reference_.poses.size();
  summary.reference_heading_source = reference_.heading_source;
  summary.distance_m = evaluator_.distance_m(summary.nominal);
  if (summary.distance_m < options.min_distance_m) {
    throw InsufficientDataError(fmt::format(
        "the vehicle barely moves: {:.1f} m of wheel odometry, at least {} m are needed",
        summary.distance_m, options.min_distance_m));
  }
  decide_difference_identifiability(reference_, options, summary);
  summary.before = evaluator_.evaluate(summary.nominal);
}

void CalibrationRun::finish(CalibrationSummary& summary) {
  const OdometryParams& e = summary.estimate;
  const bool finite_estimate = std::isfinite(e.circumference_rl_m) &&
                               std::isfinite(e.circumference_rr_m) &&
                               std::isfinite(e.track_width_m);
  summary.after = finite_estimate ? evaluator_.evaluate(e) : summary.before;
  if (summary.termination == Termination::kConverged &&
      !(finite_estimate && summary.covariance.allFinite())) {
    summary.termination = Termination::kImplausible;
    summary.message = fmt::format(
        "the estimate or its covariance is not a finite number (c_RL {}, c_RR {}): an input "
        "value is far outside its physical range; check the log's values and units",
        e.circumference_rl_m, e.circumference_rr_m);
  }
}

}  // namespace odocal
