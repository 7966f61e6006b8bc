#pragma once
// Layer 2 of the paper (section 3.2, eqs. 3-8): an EKF of the two-wheel odometry model driven by
// the wheel increments, u = [n_RL c_RL, n_RR c_RR], and corrected by the reference pose
// (h(x) = x, H = I), with the Joseph-form covariance update and a wrapped heading innovation.

#include <Eigen/Core>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/estimation/reference_filter.hpp"

namespace odocal {

struct OdometryEkfNoise {
  Eigen::Vector3d process_diagonal;      // P of the paper (per step): [x m^2, y m^2, yaw rad^2]
  Eigen::Vector3d measurement_diagonal;  // M of the paper: [1, 1, 0.01] by default (eq. 13a)
};

// The paper's process covariance for iteration i >= 1 (eq. 13b): diag(150, 150, 15) / i^q.
Eigen::Vector3d decaying_process_diagonal(int iteration, double q);

// Filtered poses x_hat_k at every reference sample (index i = wheel index - first_wheel_index).
// Starts at the first reference pose with covariance M, and restarts so where the odometry chain
// breaks (WheelStream::breaks_at). `out` is resized once and reused.
void run_odometry_ekf(const WheelStream& wheels, const ReferenceTrajectory& reference,
                      const OdometryParams& params, const OdometryEkfNoise& noise,
                      std::vector<Pose2>& out);

}  // namespace odocal
