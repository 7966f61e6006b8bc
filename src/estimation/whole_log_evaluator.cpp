#include "whole_log_evaluator.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "hot_loop.hpp"
#include "odocal/estimation/dead_reckoning.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/path_length.hpp"

namespace odocal {

WholeLogEvaluator::WholeLogEvaluator(const WheelStream& wheels,
                                     const ReferenceTrajectory& reference,
                                     const CalibrationOptions& options)
    : wheels_(wheels), reference_(reference), options_(options) {
  const std::span<const double> t = reference.times(wheels);
  align_count_ =
      options.dr_start == DeadReckoningStart::kAlignedWhole
          ? t.size()
          : static_cast<std::size_t>(
                std::upper_bound(t.begin(), t.end(), t.front() + options.dr_align_window_s) -
                t.begin());
  source_.resize(2, static_cast<Eigen::Index>(align_count_));
  target_.resize(2, static_cast<Eigen::Index>(align_count_));
  for (std::size_t i = 0; i < align_count_; ++i)
    target_.col(static_cast<Eigen::Index>(i)) = reference.poses[i].head<2>();
  for (std::size_t i = 1; i < reference.poses.size(); ++i)
    if (wheels.breaks_at(reference.first_wheel_index + i)) breaks_.push_back(i);
}

ODOCAL_HOT_LOOP DeadReckoningSummary WholeLogEvaluator::evaluate(const OdometryParams& params,
                                                                 const WheelStream& wheels) {
  std::vector<Pose2> path(reference_.poses.size());
  path[0] = reference_.poses[0];
  const std::size_t first_chain_end = breaks_.empty() ? path.size() : breaks_.front();
  dead_reckon_into(wheels, reference_.first_wheel_index, params, path, 1, first_chain_end);
  if (options_.dr_start != DeadReckoningStart::kFirstReference) align_start(path, first_chain_end);
  for (std::size_t b = 0; b < breaks_.size(); ++b) {
    const std::size_t start = breaks_[b];
    path[start] = reference_.poses[start];
    const std::size_t end = b + 1 < breaks_.size() ? breaks_[b + 1] : path.size();
    dead_reckon_into(wheels, reference_.first_wheel_index, params, path, start + 1, end);
  }
  DeadReckoningSummary summary;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Pose2& reference = reference_.poses[i];
    const double position_m = (path[i].head<2>() - reference.head<2>()).norm();
    const double heading_rad = std::abs(angle_difference(path[i].z(), reference.z()));
    summary.mean_position_m += position_m;
    summary.mean_heading_rad += heading_rad;
    summary.max_position_m = std::max(summary.max_position_m, position_m);
    summary.max_heading_rad = std::max(summary.max_heading_rad, heading_rad);
  }
  summary.mean_position_m /= static_cast<double>(path.size());
  summary.mean_heading_rad /= static_cast<double>(path.size());
  return summary;
}

double WholeLogEvaluator::distance_m(const OdometryParams& params) {
  std::vector<Pose2> path(reference_.poses.size());
  path[0] = Pose2::Zero();
  dead_reckon_into(wheels_, reference_.first_wheel_index, params, path);
  return path_length_m(path);
}

void WholeLogEvaluator::align_start(std::vector<Pose2>& path, std::size_t end) {
  const std::size_t count = std::min(align_count_, end);
  if (count < 2) return;
  for (std::size_t i = 0; i < count; ++i)
    source_.col(static_cast<Eigen::Index>(i)) = path[i].head<2>();
  const auto columns = static_cast<Eigen::Index>(count);
  const Eigen::Matrix3d T =
      Eigen::umeyama(source_.leftCols(columns), target_.leftCols(columns), false);
  const double rotation = std::atan2(T(1, 0), T(0, 0));
  for (std::size_t i = 0; i < end; ++i) {
    Pose2& pose = path[i];
    pose.head<2>() = T.topLeftCorner<2, 2>() * pose.head<2>() + T.topRightCorner<2, 1>();
    pose.z() += rotation;
  }
}

}  // namespace odocal
