#pragma once
// What calibrated rear circumferences and track mean for twist odometry (a robot's speed and
// yaw rate): the factors by which the calibrated model's speed and yaw rate differ from the
// nominal model's for the same wheel turns, with their 1-sigma from the covariance of
// [c_RL, c_RR, t_R] (docs/importing.md, "ROS bags"). Driving straight, v = (c_RL + c_RR) n / 2;
// turning on the spot, omega = (c_RL + c_RR) n / t_R.

#include <Eigen/Core>

#include "odocal/model/odometry_model.hpp"

namespace odocal {

struct OdometryScales {
  double speed_scale{};  // (c_RL + c_RR) / (c_RL0 + c_RR0)
  double sigma_speed_scale{};
  double yaw_rate_scale{};  // speed_scale * t_R0 / t_R
  double sigma_yaw_rate_scale{};
};

// `covariance`: of [c_RL, c_RR, t_R] (m^2); a held track has zero variance.
OdometryScales odometry_scales(const OdometryParams& nominal, const OdometryParams& calibrated,
                               const Eigen::Matrix3d& covariance);

}  // namespace odocal
