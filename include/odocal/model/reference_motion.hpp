#pragma once
// The motion and measurement models of layer 1, the GNSS/IMU reference filter (paper section
// 3.1, docs/calibration.md). Stateless: the filter owns the state and its covariance. Inline:
// layer 1 runs them for every sensor event.
//
// State [x, y, vx, vy, yaw, b_ax, b_ay, b_gyro]: position and velocity in the local world frame
// (m, m/s), yaw (rad, CCW from +x, unwrapped), and the biases of the body-frame accelerometer
// (m/s^2) and gyro (rad/s). The IMU input is constant over each step: the filter gives it the
// readings at the step's middle, linear between the IMU's samples.

#include <Eigen/Core>
#include <cmath>

namespace odocal {

inline constexpr int kReferenceStates = 8;
using ReferenceState = Eigen::Matrix<double, kReferenceStates, 1>;
using ReferenceJacobian = Eigen::Matrix<double, kReferenceStates, kReferenceStates>;
using ReferenceRowJacobian = Eigen::Matrix<double, 1, kReferenceStates>;

// Body-frame specific force (forward, left; m/s^2) and yaw rate (rad/s, CCW). Zero without an
// IMU: the prediction is then constant velocity and the (frozen) biases stay zero.
struct ImuSample {
  double ax_mps2{};
  double ay_mps2{};
  double wz_radps{};
  // The yaw rate's slope to the next sample (rad/s^2) and where the IMU sits in the body
  // frame from the reference point (m): an IMU ahead of the point reads its turn's -w^2 x forward
  // and dw/dt x to the left, which are not the point's.
  double wz_dot_radps2{};
  Eigen::Vector2d lever_arm_m = Eigen::Vector2d::Zero();
};

// The state dt_s later: p'' = R(yaw_mid) (a - b_a), yaw' = w - b_g, with the acceleration rotated
// by the midpoint heading yaw + (w - b_g) dt / 2 (as eq. 1 does for the odometry: the start
// heading would leak v w^2 dt / 2 of the centripetal acceleration into the along-track
// direction). J_x_x: d x(t + dt) / d x(t), optional.
inline ReferenceState predict_reference(const ReferenceState& x, const ImuSample& imu, double dt_s,
                                        ReferenceJacobian* J_x_x = nullptr);

// GNSS position: h(x) = [x, y]; J_z_x = [I 0] (the first two states).
inline Eigen::Vector2d reference_position(
    const ReferenceState& x, Eigen::Matrix<double, 2, kReferenceStates>* J_z_x = nullptr);
inline constexpr int kReferencePositionIndex = 0;

// GNSS Doppler speed over ground: h(x) = |v|. Undefined at |v| = 0 (callers gate on speed).
inline double reference_speed(const ReferenceState& x, ReferenceRowJacobian* J_z_x = nullptr);

// The same of an antenna at l (forward and left of the reference point, m; vehicle.yaml's
// gnss_x_m, gnss_y_m): its position h(x) = p + R(yaw) l, and its speed |v + w R(yaw) (-l_y, l_x)|
// with the turn w = gyro - b_g (the gyro's reading taken as known; zero without an IMU). An
// antenna ahead of the axle swings out in every turn, one to its left runs slower in a left turn.
inline Eigen::Vector2d reference_antenna_position(
    const ReferenceState& x, const Eigen::Vector2d& antenna_m,
    Eigen::Matrix<double, 2, kReferenceStates>* J_z_x = nullptr);
inline double reference_antenna_speed(const ReferenceState& x, const Eigen::Vector2d& antenna_m,
                                      double gyro_radps, ReferenceRowJacobian* J_z_x = nullptr);

// The velocity across the heading, left positive: h(x) = -sin(yaw) vx + cos(yaw) vy. A car's
// rear axle moves along its heading up to its side slip (the non-holonomic constraint).
inline double reference_lateral_velocity(const ReferenceState& x,
                                         ReferenceRowJacobian* J_z_x = nullptr);

// An absolute heading (heading.csv, or the velocity's course as a pseudo-measurement): h(x) = yaw;
// J_z_x = e_4 (the state at kReferenceYawIndex).
inline double reference_yaw(const ReferenceState& x, ReferenceRowJacobian* J_z_x = nullptr);
inline constexpr int kReferenceYawIndex = 4;

inline ReferenceState predict_reference(const ReferenceState& x, const ImuSample& imu, double dt_s,
                                        ReferenceJacobian* J_x_x) {
  const double dt = dt_s;
  const double wz = imu.wz_radps - x(7);
  const double lx = imu.lever_arm_m.x(), ly = imu.lever_arm_m.y();
  // The reference point's acceleration: the IMU's less dw/dt x l and w x (w x l) = -w^2 l.
  const double ax = imu.ax_mps2 - x(5) + imu.wz_dot_radps2 * ly + wz * wz * lx;
  const double ay = imu.ay_mps2 - x(6) - imu.wz_dot_radps2 * lx + wz * wz * ly;
  const double yaw_mid = x(4) + 0.5 * wz * dt;
  const double c = std::cos(yaw_mid), s = std::sin(yaw_mid);
  const Eigen::Vector2d a_world(c * ax - s * ay, s * ax + c * ay);

  ReferenceState next = x;
  next.head<2>() += dt * x.segment<2>(2) + 0.5 * dt * dt * a_world;
  next.segment<2>(2) += dt * a_world;
  next(4) += dt * wz;

  if (J_x_x != nullptr) {
    // d a_world / d yaw_mid; yaw_mid depends on yaw (1) and on the gyro bias (-dt / 2).
    const Eigen::Vector2d d_a_d_yaw(-s * ax - c * ay, c * ax - s * ay);
    Eigen::Matrix2d rotation;
    rotation << c, -s, s, c;
    ReferenceJacobian& J = *J_x_x;
    J.setIdentity();
    J.block<2, 2>(0, 2) = dt * Eigen::Matrix2d::Identity();
    J.block<2, 1>(0, 4) = 0.5 * dt * dt * d_a_d_yaw;
    J.block<2, 1>(2, 4) = dt * d_a_d_yaw;
    J.block<2, 2>(0, 5) = -0.5 * dt * dt * rotation;
    J.block<2, 2>(2, 5) = -dt * rotation;
    // The gyro bias turns the midpoint heading and, through w^2 l, the body-frame acceleration.
    const Eigen::Vector2d d_a_d_bias =
        -0.5 * dt * d_a_d_yaw - 2.0 * wz * (rotation * imu.lever_arm_m);
    J.block<2, 1>(0, 7) = 0.5 * dt * dt * d_a_d_bias;
    J.block<2, 1>(2, 7) = dt * d_a_d_bias;
    J(4, 7) = -dt;
  }
  return next;
}

inline Eigen::Vector2d reference_position(const ReferenceState& x,
                                          Eigen::Matrix<double, 2, kReferenceStates>* J_z_x) {
  if (J_z_x != nullptr) {
    J_z_x->setZero();
    J_z_x->leftCols<2>().setIdentity();
  }
  return x.head<2>();
}

inline double reference_speed(const ReferenceState& x, ReferenceRowJacobian* J_z_x) {
  const double speed = x.segment<2>(2).norm();
  if (J_z_x != nullptr) {
    J_z_x->setZero();
    (*J_z_x)(2) = x(2) / speed;
    (*J_z_x)(3) = x(3) / speed;
  }
  return speed;
}

inline Eigen::Vector2d reference_antenna_position(
    const ReferenceState& x, const Eigen::Vector2d& antenna_m,
    Eigen::Matrix<double, 2, kReferenceStates>* J_z_x) {
  const double c = std::cos(x(4)), s = std::sin(x(4));
  const Eigen::Vector2d rotated(c * antenna_m.x() - s * antenna_m.y(),
                                s * antenna_m.x() + c * antenna_m.y());
  if (J_z_x != nullptr) {
    J_z_x->setZero();
    J_z_x->leftCols<2>().setIdentity();
    J_z_x->col(4) = Eigen::Vector2d(-rotated.y(), rotated.x());
  }
  return x.head<2>() + rotated;
}

inline double reference_antenna_speed(const ReferenceState& x, const Eigen::Vector2d& antenna_m,
                                      double gyro_radps, ReferenceRowJacobian* J_z_x) {
  const double c = std::cos(x(4)), s = std::sin(x(4));
  // R(yaw) (-l_y, l_x): the antenna's velocity per unit turn, and its change with yaw.
  const Eigen::Vector2d swing(-c * antenna_m.y() - s * antenna_m.x(),
                              -s * antenna_m.y() + c * antenna_m.x());
  const double turn = gyro_radps - x(7);
  const Eigen::Vector2d velocity = x.segment<2>(2) + turn * swing;
  const double speed = velocity.norm();
  if (J_z_x != nullptr) {
    const Eigen::Vector2d direction = velocity / speed;
    J_z_x->setZero();
    J_z_x->segment<2>(2) = direction.transpose();
    (*J_z_x)(4) = turn * direction.dot(Eigen::Vector2d(-swing.y(), swing.x()));
    (*J_z_x)(7) = -direction.dot(swing);
  }
  return speed;
}

inline double reference_lateral_velocity(const ReferenceState& x, ReferenceRowJacobian* J_z_x) {
  const double c = std::cos(x(4)), s = std::sin(x(4));
  if (J_z_x != nullptr) {
    J_z_x->setZero();
    (*J_z_x)(2) = -s;
    (*J_z_x)(3) = c;
    (*J_z_x)(4) = -c * x(2) - s * x(3);
  }
  return -s * x(2) + c * x(3);
}

inline double reference_yaw(const ReferenceState& x, ReferenceRowJacobian* J_z_x) {
  if (J_z_x != nullptr) {
    J_z_x->setZero();
    (*J_z_x)(4) = 1.0;
  }
  return x(4);
}

}  // namespace odocal
