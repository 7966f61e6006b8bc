#pragma once
// Where a sensor mounted off the rear axle's centre is (vehicle.yaml's gnss_x_m, gnss_y_m): the
// fixes are its position, not the axle's, wherever a pose is compared with them.

#include <Eigen/Geometry>

#include "odocal/model/odometry_model.hpp"

namespace odocal {

// The world position of a sensor `place_m` forward and left of the rear axle's centre when the
// axle's pose is `pose`.
inline Eigen::Vector2d mounted_position(const Pose2& pose, const Eigen::Vector2d& place_m) {
  return pose.head<2>() + Eigen::Rotation2Dd(pose.z()) * place_m;
}

}  // namespace odocal
