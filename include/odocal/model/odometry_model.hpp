#pragma once
// The two-wheel odometry model of the paper (eqs. 1-2): the rear wheels' revolution increments
// n_RL,k and n_RR,k, scaled by their circumferences, move the reference point (rear-axle
// midpoint). Stateless: filters own the state.

#include <Eigen/Core>

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

BodyIncrement body_increment(const WheelIncrement& n, const OdometryParams& params);

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

}  // namespace odocal
