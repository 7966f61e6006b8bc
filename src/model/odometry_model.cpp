#include "odocal/model/odometry_model.hpp"

#include <cmath>

namespace odocal {

Pose2 predict_pose(const Pose2& pose, const WheelIncrement& n, const OdometryParams& params,
                   double side_slip_rad, const OdometryJacobians& jacobians) {
  const BodyIncrement step = body_increment(n, params);
  const double course_rad = pose.z() + 0.5 * step.yaw_rad + side_slip_rad;
  return predict_pose_on_course(pose, n, step, {std::cos(course_rad), std::sin(course_rad)}, params,
                                jacobians);
}

}  // namespace odocal
