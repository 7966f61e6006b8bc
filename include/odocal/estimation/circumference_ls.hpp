#pragma once
// Layer 3 of the paper (section 3.3, eqs. 9-12): weighted least squares for the rear wheel
// circumferences from the EKF poses and the reference,
//   z_k = [x~_k - x^_{k-1}, y~_k - y^_{k-1}, yaw~_k - yaw^_{k-1}],
//   phi_k = [[n_RL cos(yaw^_{k-1}) / 2, n_RR cos(yaw^_{k-1}) / 2],
//            [n_RL sin(yaw^_{k-1}) / 2, n_RR sin(yaw^_{k-1}) / 2],
//            [-n_RL / t_R,              n_RR / t_R]],
// W = diag(1, 1, 10) per sample. Rows may be summed over windows of `window_samples` samples
// (1 = the paper): a sum of rows of eq. 9 is still exact, and the encoder quantisation in the
// summed increments telescopes to one tick per window instead of one tick per sample, which
// removes the errors-in-variables bias of the per-sample fit (docs/calibration.md). A window
// that spans a break of the odometry chain (a wheel gap) gives no row. Solved by a
// Householder QR of the weighted rows (no normal equations, one allocation per fit).

#include <Eigen/Core>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/estimation/reference_filter.hpp"

namespace odocal {

struct CircumferenceFit {
  Eigen::Vector2d circumference_m = Eigen::Vector2d::Zero();  // [c_RL, c_RR]
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();  // residual variance times (Phi^T W Phi)^-1
  double condition_number{};                             // of sqrt(W) Phi
  double residual_rms{};                                 // weighted
  std::size_t rows{};
};

// x_hat[i] is the EKF pose at reference sample i. Weights: W = diag(w[0], w[1], w[2]).
CircumferenceFit fit_circumferences(const WheelStream& wheels, const ReferenceTrajectory& reference,
                                    const std::vector<Pose2>& x_hat, double track_width_m,
                                    const Eigen::Vector3d& weights, int window_samples = 1);

// The same rows with one unknown, a common scale k of the given circumferences: c = k c_ratio.
// For logs that cannot separate the left and right wheels.
CircumferenceFit fit_common_scale(const WheelStream& wheels, const ReferenceTrajectory& reference,
                                  const std::vector<Pose2>& x_hat, double track_width_m,
                                  const Eigen::Vector3d& weights, int window_samples,
                                  const Eigen::Vector2d& c_ratio);

}  // namespace odocal
