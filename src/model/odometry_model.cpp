#include "odocal/model/odometry_model.hpp"

#include <cmath>

namespace odocal {

BodyIncrement body_increment(const WheelIncrement& n, const OdometryParams& params) {
  const double left_m = n.rev_rl * params.circumference_rl_m;
  const double right_m = n.rev_rr * params.circumference_rr_m;
  return {0.5 * (left_m + right_m), (right_m - left_m) / params.track_width_m};
}

Pose2 predict_pose(const Pose2& pose, const WheelIncrement& n, const OdometryParams& params,
                   double side_slip_rad, const OdometryJacobians& jacobians) {
  const BodyIncrement step = body_increment(n, params);
  const double course_rad = pose.z() + 0.5 * step.yaw_rad + side_slip_rad;
  const double cos_course = std::cos(course_rad);
  const double sin_course = std::sin(course_rad);

  // A change (d_distance, d_yaw) of the increment moves the pose by this much.
  const auto pose_change = [&](double d_distance, double d_yaw) {
    return Eigen::Vector3d(d_distance * cos_course - step.distance_m * sin_course * 0.5 * d_yaw,
                           d_distance * sin_course + step.distance_m * cos_course * 0.5 * d_yaw,
                           d_yaw);
  };

  if (jacobians.J_pose_pose != nullptr) {
    *jacobians.J_pose_pose << 1.0, 0.0, -step.distance_m * sin_course,  //
        0.0, 1.0, step.distance_m * cos_course,                         //
        0.0, 0.0, 1.0;
  }
  const double c_rl = params.circumference_rl_m;
  const double c_rr = params.circumference_rr_m;
  const double track = params.track_width_m;
  if (jacobians.J_pose_wheels != nullptr) {
    jacobians.J_pose_wheels->col(0) = pose_change(0.5 * c_rl, -c_rl / track);
    jacobians.J_pose_wheels->col(1) = pose_change(0.5 * c_rr, c_rr / track);
  }
  if (jacobians.J_pose_params != nullptr) {
    jacobians.J_pose_params->col(0) = pose_change(0.5 * n.rev_rl, -n.rev_rl / track);
    jacobians.J_pose_params->col(1) = pose_change(0.5 * n.rev_rr, n.rev_rr / track);
    jacobians.J_pose_params->col(2) = pose_change(0.0, -step.yaw_rad / track);
  }
  if (jacobians.J_pose_side_slip != nullptr) {
    *jacobians.J_pose_side_slip << -step.distance_m * sin_course, step.distance_m * cos_course, 0.0;
  }
  return {pose.x() + step.distance_m * cos_course, pose.y() + step.distance_m * sin_course,
          pose.z() + step.yaw_rad};
}

}  // namespace odocal
