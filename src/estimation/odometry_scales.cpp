#include "odocal/estimation/odometry_scales.hpp"

#include <cmath>

namespace odocal {

OdometryScales odometry_scales(const OdometryParams& nominal, const OdometryParams& calibrated,
                               const Eigen::Matrix3d& covariance) {
  const double nominal_sum = nominal.circumference_rl_m + nominal.circumference_rr_m;
  const double speed =
      (calibrated.circumference_rl_m + calibrated.circumference_rr_m) / nominal_sum;
  const double yaw = speed * nominal.track_width_m / calibrated.track_width_m;
  // First-order propagation: J of [speed, yaw] over [c_RL, c_RR, t_R].
  Eigen::Matrix<double, 2, 3> J;
  J << 1.0 / nominal_sum, 1.0 / nominal_sum, 0.0,
      nominal.track_width_m / (calibrated.track_width_m * nominal_sum),
      nominal.track_width_m / (calibrated.track_width_m * nominal_sum),
      -yaw / calibrated.track_width_m;
  const Eigen::Matrix2d scales = J * covariance * J.transpose();
  return {speed, std::sqrt(scales(0, 0)), yaw, std::sqrt(scales(1, 1))};
}

}  // namespace odocal
