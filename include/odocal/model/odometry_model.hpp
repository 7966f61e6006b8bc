#pragma once
// The two-wheel odometry model of the paper (eqs. 1-2): the rear wheels' revolution increments
// n_RL,k and n_RR,k, scaled by their circumferences, move the reference point (rear-axle
// midpoint). Stateless: filters own the state.

#include <Eigen/Core>

#include "odocal/model/stepwise_cos_sin.hpp"

namespace odocal {

// Pose of the vehicle reference point in the local world frame: [x_m, y_m, yaw_rad].
using Pose2 = Eigen::Vector3d;

// Kinematic parameters of the rear axle.
struct OdometryParams {
  double circumference_rl_m{};  // c_RL = 2 pi r_RL (dynamic rolling radius)
  double circumference_rr_m{};  // c_RR
  double track_width_m{};       // t_R, rear track
};

// Revolution increments of the rear wheels over one sample interval (signed: negative = reverse).
struct WheelIncrement {
  double rev_rl{};  // n_RL,k
  double rev_rr{};  // n_RR,k
};

// Arc length and yaw increment of the reference point over one interval (eq. 2 times dt).
struct BodyIncrement {
  double distance_m{};  // v_k * dt
  double yaw_rad{};     // omega_k * dt
};

inline BodyIncrement body_increment(const WheelIncrement& n, const OdometryParams& params) {
  const double left_m = n.rev_rl * params.circumference_rl_m;
  const double right_m = n.rev_rr * params.circumference_rr_m;
  return {0.5 * (left_m + right_m), (right_m - left_m) / params.track_width_m};
}

using OdometryJacobianPose = Eigen::Matrix3d;                // d pose_k / d pose_{k-1}
using OdometryJacobianWheels = Eigen::Matrix<double, 3, 2>;  // d pose_k / d [n_RL, n_RR]
using OdometryJacobianParams = Eigen::Matrix3d;              // d pose_k / d [c_RL, c_RR, t_R]
using OdometryJacobianSideSlip = Eigen::Vector3d;            // d pose_k / d beta_k

// Optional Jacobian outputs of predict_pose; leave a pointer null to skip that block.
struct OdometryJacobians {
  OdometryJacobianPose* J_pose_pose = nullptr;
  OdometryJacobianWheels* J_pose_wheels = nullptr;
  OdometryJacobianParams* J_pose_params = nullptr;
  OdometryJacobianSideSlip* J_pose_side_slip = nullptr;
};

// Eq. (1): pose_k from pose_{k-1} with the midpoint heading theta + omega dt / 2 + beta.
// The result's yaw is not wrapped (continuous integration); wrap when comparing.
Pose2 predict_pose(const Pose2& pose, const WheelIncrement& n, const OdometryParams& params,
                   double side_slip_rad = 0.0, const OdometryJacobians& jacobians = {});

// Eq. (1) for callers that track the course's cos and sin themselves (StepwiseCosSin): `step`
// is body_increment(n, params), `course` the cos and sin of pose.z() + step.yaw_rad / 2 + beta.
// Inline because the calibration loop runs it per sample and iteration.
inline Pose2 predict_pose_on_course(const Pose2& pose, const WheelIncrement& n,
                                    const BodyIncrement& step, const CosSin& course,
                                    const OdometryParams& params,
                                    const OdometryJacobians& jacobians = {}) {
  // A change (d_distance, d_yaw) of the increment moves the pose by this much.
  const auto pose_change = [&](double d_distance, double d_yaw) {
    return Eigen::Vector3d(d_distance * course.cos - step.distance_m * course.sin * 0.5 * d_yaw,
                           d_distance * course.sin + step.distance_m * course.cos * 0.5 * d_yaw,
                           d_yaw);
  };
  if (jacobians.J_pose_pose != nullptr) {
    *jacobians.J_pose_pose << 1.0, 0.0, -step.distance_m * course.sin,  //
        0.0, 1.0, step.distance_m * course.cos,                         //
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
    *jacobians.J_pose_side_slip << -step.distance_m * course.sin, step.distance_m * course.cos, 0.0;
  }
  return {pose.x() + step.distance_m * course.cos, pose.y() + step.distance_m * course.sin,
          pose.z() + step.yaw_rad};
}

}  // namespace odocal
