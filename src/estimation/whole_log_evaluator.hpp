#pragma once
// Dead reckoning of the whole log with given parameters, compared with the reference (paper
// section 4: "the two-wheel vehicle model with the new parameters is simulated on the whole
// dataset"). The start pose follows CalibrationOptions::dr_start. Both live on the wheel time
// base, so the comparison is index by index. The dead-reckoned path lives only while one call
// runs (24 bytes per wheel sample): a long log's batch solve, which keeps the evaluator, must not
// carry it at its peak. Where the odometry chain breaks (a wheel gap), the dead reckoning
// restarts from the reference pose.

#include <Eigen/Core>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/estimation/calibration_options.hpp"
#include "odocal/estimation/calibration_summary.hpp"
#include "odocal/estimation/reference_filter.hpp"

namespace odocal {

class WholeLogEvaluator {
 public:
  // Keeps references to all three: they must outlive the evaluator.
  WholeLogEvaluator(const WheelStream& wheels, const ReferenceTrajectory& reference,
                    const CalibrationOptions& options);

  DeadReckoningSummary evaluate(const OdometryParams& params) { return evaluate(params, wheels_); }
  // With other increments of the same samples (the wheels with a tyre model applied).
  DeadReckoningSummary evaluate(const OdometryParams& params, const WheelStream& wheels);
  // Length of the dead-reckoned path over the reference span.
  double distance_m(const OdometryParams& params);

 private:
  // Moves path[0, end) rigidly so that its first positions (at most align_count_) best fit the
  // reference.
  void align_start(std::vector<Pose2>& path, std::size_t end);

  const WheelStream& wheels_;
  const ReferenceTrajectory& reference_;
  const CalibrationOptions& options_;
  Eigen::Matrix2Xd source_, target_;
  std::size_t align_count_{};
  std::vector<std::size_t> breaks_;  // reference indices where the odometry chain breaks
};

}  // namespace odocal
