#pragma once
// Residuals of the batch calibration (docs/calibration.md, "Batch maximum likelihood"), as
// templated functors for Ceres' automatic differentiation. Every residual is whitened (divided
// by its standard deviation or multiplied by a square-root information matrix).
//
// Parameter blocks: pose [x m, y m, yaw rad] per keyframe; params [c_RL m, c_RR m, t_R m, the
// tyre model's coefficients k_speed, k_lateral, k_drive, k_brake (odocal/model/tyre_model.hpp)];
// lever [x m forward, y m left] (GNSS antenna in the vehicle frame); latency [s] (a fix stamped t
// reports the position at t - latency); gnss_bias [x m, y m] per keyframe (Gauss-Markov GNSS
// error, constant zero when not modelled); heading_bias [rad]; gyro_bias [rad/s]; count
// [n_RL rev, n_RR rev] per keyframe: the encoder quantisation error of the cumulative counts
// there (the true count is the logged one plus this), so that quantisation shifts motion between
// neighbouring segments instead of accumulating.

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <cmath>

#include "odocal/model/tyre_model.hpp"

namespace odocal::batch {

inline constexpr int kParams = 3 + TyreModel::kCoefficients;
using ParamsVector = Eigen::Matrix<double, kParams, 1>;
using ParamsJacobian = Eigen::Matrix<double, 3, kParams>;

// The pre-integrated odometry from a keyframe to one instant, linear in the parameters around
// the values it was integrated with and in the keyframe's count error q (which takes q from the
// segment's first increment): delta(p, q) = delta + J_p (p - p_lin) - J_first q.
struct RelativeMotion {
  Eigen::Vector3d delta = Eigen::Vector3d::Zero();
  ParamsJacobian J_delta_params = ParamsJacobian::Zero();
  Eigen::Matrix<double, 3, 2> J_delta_first_increment = Eigen::Matrix<double, 3, 2>::Zero();
  ParamsVector params_lin = ParamsVector::Zero();

  template <typename T>
  Eigen::Matrix<T, 3, 1> at(const T* params, const T* count) const {
    Eigen::Matrix<T, kParams, 1> change;
    for (int p = 0; p < kParams; ++p) change(p) = params[p] - params_lin(p);
    const Eigen::Matrix<T, 2, 1> count_error(count[0], count[1]);
    return delta.cast<T>() + J_delta_params.cast<T>() * change -
           J_delta_first_increment.cast<T>() * count_error;
  }
};

template <typename T>
T wrapped(const T& angle) {
  using std::atan2, std::cos, std::sin;
  return atan2(sin(angle), cos(angle));
}

// Odometry between keyframes i and i+1: the relative pose of i+1 seen from i against the
// pre-integrated wheel motion (its last increment gains the end count error), weighted by the
// propagated slip covariance.
struct OdometryResidual {
  RelativeMotion motion;
  Eigen::Matrix<double, 3, 2> J_end_last_increment;
  Eigen::Matrix3d sqrt_information;

  template <typename T>
  bool operator()(const T* pose_a, const T* pose_b, const T* params, const T* count_a,
                  const T* count_b, T* residual) const {
    using std::cos, std::sin;
    const Eigen::Matrix<T, 2, 1> end_error(count_b[0], count_b[1]);
    const Eigen::Matrix<T, 3, 1> delta =
        motion.at(params, count_a) + J_end_last_increment.cast<T>() * end_error;
    const T c = cos(pose_a[2]), s = sin(pose_a[2]);
    const T dx = pose_b[0] - pose_a[0], dy = pose_b[1] - pose_a[1];
    const Eigen::Matrix<T, 3, 1> error(c * dx + s * dy - delta(0), -s * dx + c * dy - delta(1),
                                       wrapped(T(pose_b[2] - pose_a[2] - delta(2))));
    Eigen::Map<Eigen::Matrix<T, 3, 1>> whitened(residual);
    whitened = sqrt_information.cast<T>() * error;
    return true;
  }
};

// One GNSS fix, at an instant between keyframe i (pose) and the next. Its motion is that of the
// instant the fix reports at the latency the problem was linearised at, moved on by the velocity
// times that latency (BatchProblem::visit_fixes), so that subtracting the velocity times the
// latency takes only the latency's change since to first order.
struct GnssResidual {
  RelativeMotion motion;
  Eigen::Vector2d velocity_in_keyframe;  // of the reference point at the fix, keyframe frame
  Eigen::Vector2d measured;
  double sigma_m{};

  template <typename T>
  bool operator()(const T* pose, const T* params, const T* lever, const T* latency, const T* bias,
                  const T* count, T* residual) const {
    using std::cos, std::sin;
    const Eigen::Matrix<T, 3, 1> delta = motion.at(params, count);
    const T c = cos(pose[2]), s = sin(pose[2]);
    const T yaw = pose[2] + delta(2);
    const T cy = cos(yaw), sy = sin(yaw);
    const T vx = c * velocity_in_keyframe.x() - s * velocity_in_keyframe.y();
    const T vy = s * velocity_in_keyframe.x() + c * velocity_in_keyframe.y();
    const T x = pose[0] + c * delta(0) - s * delta(1) + cy * lever[0] - sy * lever[1] -
                vx * latency[0] + bias[0];
    const T y = pose[1] + s * delta(0) + c * delta(1) + sy * lever[0] + cy * lever[1] -
                vy * latency[0] + bias[1];
    residual[0] = (x - measured.x()) / sigma_m;
    residual[1] = (y - measured.y()) / sigma_m;
    return true;
  }
};

// One magnetic heading sample.
struct HeadingResidual {
  RelativeMotion motion;
  double measured_rad{};
  double sigma_rad{};

  template <typename T>
  bool operator()(const T* pose, const T* params, const T* heading_bias, const T* count,
                  T* residual) const {
    const Eigen::Matrix<T, 3, 1> delta = motion.at(params, count);
    residual[0] = wrapped(T(pose[2] + delta(2) + heading_bias[0] - measured_rad)) / sigma_rad;
    return true;
  }
};

// The gyro's yaw change over a keyframe interval (integrated yaw rate) against the poses' change,
// their difference wrapped: the gyro's own turn may exceed +-pi in a long interval, their error
// may not.
struct GyroResidual {
  double integrated_rad{};
  double duration_s{};
  double sigma_rad{};

  template <typename T>
  bool operator()(const T* pose_a, const T* pose_b, const T* gyro_bias, T* residual) const {
    // As the odometry's: poses a whole turn apart are the same heading, and the layer-1
    // reference that starts the poses may settle a turn away from its first yaw.
    const T error = pose_b[2] - pose_a[2] - (integrated_rad - gyro_bias[0] * duration_s);
    residual[0] = wrapped(error) / sigma_rad;
    return true;
  }
};

// First-order Gauss-Markov GNSS error between consecutive keyframes: b' = phi b + w.
struct GaussMarkovResidual {
  double phi{};
  double sigma_m{};  // of w

  template <typename T>
  bool operator()(const T* bias_a, const T* bias_b, T* residual) const {
    residual[0] = (bias_b[0] - phi * bias_a[0]) / sigma_m;
    residual[1] = (bias_b[1] - phi * bias_a[1]) / sigma_m;
    return true;
  }
};

// The encoder quantisation at a keyframe: a rounded count is off by U(-1/2, 1/2) tick, taken as
// Gaussian with the same sigma (1/sqrt(12) tick, in revolutions).
struct CountErrorPrior {
  double sigma_rev{};

  template <typename T>
  bool operator()(const T* count, T* residual) const {
    residual[0] = count[0] / sigma_rev;
    residual[1] = count[1] / sigma_rev;
    return true;
  }
};

// The Gauss-Markov error's stationary prior at the first keyframe.
struct GaussMarkovPrior {
  double sigma_m{};

  template <typename T>
  bool operator()(const T* bias, T* residual) const {
    residual[0] = bias[0] / sigma_m;
    residual[1] = bias[1] / sigma_m;
    return true;
  }
};

// The plain model's track width under its prior: vehicle.yaml's, uncertain by
// track_width_uncertainty (BatchProblem::set_track_prior).
struct TrackWidthPrior {
  double track_m{};
  double sigma_m{};

  template <typename T>
  bool operator()(const T* params, T* residual) const {
    residual[0] = (params[2] - track_m) / sigma_m;
    return true;
  }
};

}  // namespace odocal::batch
