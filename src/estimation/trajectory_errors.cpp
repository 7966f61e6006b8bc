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

TrajectoryErrors trajectory_errors(const PoseStream& trajectory, const ReferencePath& reference) {
  TrajectoryErrors errors;
  double position_sum_m = 0.0;
  for (std::size_t k = 0; k < reference.position_t_s.size(); ++k) {
    const auto pose = interpolate_pose(trajectory, reference.position_t_s[k]);
    if (!pose) continue;
    const double error_m = std::hypot(pose->x() - reference.x_m[k], pose->y() - reference.y_m[k]);
    position_sum_m += error_m;
    errors.max_position_m = std::max(errors.max_position_m, error_m);
    errors.final_position_m = error_m;
    ++errors.position_samples;
  }
  if (errors.position_samples == 0) {
    throw Error("no sample of " + reference.name + " lies inside the trajectory's time span");
  }
  errors.mean_position_m = position_sum_m / static_cast<double>(errors.position_samples);

  double heading_sum_rad = 0.0;
  for (std::size_t k = 0; k < reference.heading_t_s.size(); ++k) {
    const auto pose = interpolate_pose(trajectory, reference.heading_t_s[k]);
    if (!pose) continue;
    const double error_rad = std::abs(angle_difference(pose->z(), reference.heading_rad[k]));
    heading_sum_rad += error_rad;
    errors.max_heading_rad = std::max(errors.max_heading_rad, error_rad);
    ++errors.heading_samples;
  }
  if (errors.heading_samples > 0) {
    errors.mean_heading_rad = heading_sum_rad / static_cast<double>(errors.heading_samples);
  }

  errors.distance_m = path_length_m(trajectory.pose);
  errors.final_drift_percent =
      errors.distance_m > 0.0 ? 100.0 * errors.final_position_m / errors.distance_m : 0.0;
  return errors;
}

}  // namespace odocal
