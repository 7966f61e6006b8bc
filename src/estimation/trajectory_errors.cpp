#include "odocal/estimation/trajectory_errors.hpp"

#include <algorithm>
#include <cmath>

#include "odocal/error.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/path_length.hpp"

namespace odocal {

ReferencePath reference_from_poses(const PoseStream& poses, std::string name) {
  ReferencePath reference;
  reference.name = std::move(name);
  reference.position_t_s = poses.t_s;
  reference.heading_t_s = poses.t_s;
  reference.x_m.reserve(poses.size());
  reference.y_m.reserve(poses.size());
  reference.heading_rad.reserve(poses.size());
  for (const Pose2& pose : poses.pose) {
    reference.x_m.push_back(pose.x());
    reference.y_m.push_back(pose.y());
    reference.heading_rad.push_back(pose.z());
  }
  return reference;
}

ReferencePath reference_from_gnss(const GnssStream& gnss, const HeadingStream* heading) {
  ReferencePath reference;
  reference.name = heading != nullptr ? "gnss.csv + heading.csv" : "gnss.csv";
  reference.position_t_s = gnss.t_s;
  reference.x_m = gnss.x_m;
  reference.y_m = gnss.y_m;
  if (heading != nullptr) {
    reference.heading_t_s = heading->t_s;
    reference.heading_rad = heading->heading_rad;
  }
  return reference;
}

void TrajectoryErrorSum::add(const PoseStream& piece, const ReferencePath& reference) {
  if (piece.size() == 0) return;
  // Reference samples from the piece's first pose on (the first piece), else after it.
  const auto from = [&](const std::vector<double>& t_s) {
    const auto at = first_piece_ ? std::lower_bound(t_s.begin(), t_s.end(), piece.t_s.front())
                                 : std::upper_bound(t_s.begin(), t_s.end(), piece.t_s.front());
    return static_cast<std::size_t>(at - t_s.begin());
  };
  for (std::size_t k = from(reference.position_t_s); k < reference.position_t_s.size(); ++k) {
    const auto pose = interpolate_pose(piece, reference.position_t_s[k]);
    if (!pose) break;
    const double error_m = std::hypot(pose->x() - reference.x_m[k], pose->y() - reference.y_m[k]);
    position_sum_m_ += error_m;
    sums_.max_position_m = std::max(sums_.max_position_m, error_m);
    sums_.final_position_m = error_m;
    ++sums_.position_samples;
  }
  for (std::size_t k = from(reference.heading_t_s); k < reference.heading_t_s.size(); ++k) {
    const auto pose = interpolate_pose(piece, reference.heading_t_s[k]);
    if (!pose) break;
    const double error_rad = std::abs(angle_difference(pose->z(), reference.heading_rad[k]));
    heading_sum_rad_ += error_rad;
    sums_.max_heading_rad = std::max(sums_.max_heading_rad, error_rad);
    ++sums_.heading_samples;
  }
  sums_.distance_m += path_length_m(piece.pose);
  first_piece_ = false;
}

TrajectoryErrors TrajectoryErrorSum::result(const std::string& reference_name) const {
  TrajectoryErrors errors = sums_;
  if (errors.position_samples == 0)
    throw Error("no sample of " + reference_name + " lies inside the trajectory's time span");
  errors.mean_position_m = position_sum_m_ / static_cast<double>(errors.position_samples);
  if (errors.heading_samples > 0)
    errors.mean_heading_rad = heading_sum_rad_ / static_cast<double>(errors.heading_samples);
  errors.final_drift_percent =
      errors.distance_m > 0.0 ? 100.0 * errors.final_position_m / errors.distance_m : 0.0;
  return errors;
}

TrajectoryErrors trajectory_errors(const PoseStream& trajectory, const ReferencePath& reference) {
  TrajectoryErrorSum sum;
  sum.add(trajectory, reference);
  return sum.result(reference.name);
}

}  // namespace odocal
