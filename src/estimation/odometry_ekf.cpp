#include "odocal/estimation/odometry_ekf.hpp"

#include <Eigen/LU>
#include <cmath>

#include "hot_loop.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/odometry_model.hpp"

namespace odocal {
namespace {

// Eq. 5b for eq. 1's Jacobian, F = I + [a, b, 0]^T e_yaw^T (only the heading column couples
// the states): sigma plus rank-two terms, a fifth of the work of two general 3x3 products.
Eigen::Matrix3d propagate_covariance(const Eigen::Matrix3d& sigma, const OdometryJacobianPose& F,
                                     const Eigen::Vector3d& process_diagonal) {
  const double a = F(0, 2), b = F(1, 2);
  const double s02 = sigma(0, 2) + a * sigma(2, 2), s12 = sigma(1, 2) + b * sigma(2, 2);
  Eigen::Matrix3d out;
  out(0, 0) = sigma(0, 0) + a * (sigma(0, 2) + s02) + process_diagonal(0);
  out(1, 1) = sigma(1, 1) + b * (sigma(1, 2) + s12) + process_diagonal(1);
  out(2, 2) = sigma(2, 2) + process_diagonal(2);
  out(0, 1) = out(1, 0) = sigma(0, 1) + a * sigma(1, 2) + b * s02;
  out(0, 2) = out(2, 0) = s02;
  out(1, 2) = out(2, 1) = s12;
  return out;
}

// S^-1 = adjugate / det for the symmetric positive definite S = sigma + M, from its six distinct
// cofactors. S >= M has eigenvalues >= min M, so the closed form is as accurate here as a
// Cholesky solve. Kept apart so that the state update can start on the adjugate while the
// division is still in flight (the filter's speed is the latency of its step-to-step chain).
struct SymmetricInverse {
  Eigen::Matrix3d adjugate;
  double inverse_det;
};

SymmetricInverse symmetric_inverse(const Eigen::Matrix3d& S) {
  Eigen::Matrix3d adjugate;
  adjugate(0, 0) = S(1, 1) * S(2, 2) - S(1, 2) * S(1, 2);
  adjugate(0, 1) = S(0, 2) * S(1, 2) - S(0, 1) * S(2, 2);
  adjugate(0, 2) = S(0, 1) * S(1, 2) - S(0, 2) * S(1, 1);
  adjugate(1, 1) = S(0, 0) * S(2, 2) - S(0, 2) * S(0, 2);
  adjugate(1, 2) = S(0, 1) * S(0, 2) - S(0, 0) * S(1, 2);
  adjugate(2, 2) = S(0, 0) * S(1, 1) - S(0, 1) * S(0, 1);
  adjugate.triangularView<Eigen::StrictlyLower>() = adjugate.transpose();
  const double det = S(0, 0) * adjugate(0, 0) + S(0, 1) * adjugate(0, 1) + S(0, 2) * adjugate(0, 2);
  return {adjugate, 1.0 / det};
}

// Joseph form of eq. 7b, (I - G) sigma (I - G)^T + G M G^T, evaluated on the upper triangle
// only and mirrored: symmetric by construction.
Eigen::Matrix3d joseph_update(const Eigen::Matrix3d& sigma, const Eigen::Matrix3d& G,
                              const Eigen::Vector3d& measurement_diagonal) {
  const Eigen::Matrix3d I_G = Eigen::Matrix3d::Identity() - G;
  const Eigen::Matrix3d I_G_sigma = I_G.lazyProduct(sigma);
  const Eigen::Matrix3d G_M = G * measurement_diagonal.asDiagonal();
  Eigen::Matrix3d out;
  out.triangularView<Eigen::Upper>() =
      I_G_sigma.lazyProduct(I_G.transpose()) + G_M.lazyProduct(G.transpose());
  out.triangularView<Eigen::StrictlyLower>() = out.transpose();
  return out;
}

}  // namespace

Eigen::Vector3d decaying_process_diagonal(int iteration, double q) {
  const double scale = 1.0 / std::pow(static_cast<double>(iteration), q);
  return Eigen::Vector3d(150.0, 150.0, 15.0) * scale;
}

ODOCAL_HOT_LOOP void run_odometry_ekf(const WheelStream& wheels,
                                      const ReferenceTrajectory& reference,
                                      const OdometryParams& params, const OdometryEkfNoise& noise,
                                      std::vector<Pose2>& out) {
  const std::size_t n = reference.poses.size();
  out.resize(n);
  const Eigen::Matrix3d M = noise.measurement_diagonal.asDiagonal();
  Pose2 x = reference.poses.pose[0];
  Eigen::Matrix3d sigma = M;
  out[0] = x;
  OdometryJacobianPose F;
  StepwiseCosSin course_cos_sin;
  for (std::size_t i = 1; i < n; ++i) {
    const WheelIncrement increment = wheels.increment(reference.first_wheel_index + i);
    const BodyIncrement step = body_increment(increment, params);
    const CosSin course = course_cos_sin(x.z() + 0.5 * step.yaw_rad);
    x = predict_pose_on_course(x, increment, step, course, params, {.J_pose_pose = &F});  // eq. 5a
    sigma = propagate_covariance(sigma, F, noise.process_diagonal);                       // eq. 5b
    Eigen::Vector3d innovation = reference.poses.pose[i] - x;                             // eq. 7a
    innovation.z() = angle_difference(reference.poses.pose[i].z(), x.z());
    const SymmetricInverse S_inverse = symmetric_inverse(sigma + M);
    const Eigen::Matrix3d sigma_adjugate = sigma.lazyProduct(S_inverse.adjugate);
    const Eigen::Matrix3d G = sigma_adjugate * S_inverse.inverse_det;  // eq. 8
    x += (sigma_adjugate * innovation) * S_inverse.inverse_det;
    sigma = joseph_update(sigma, G, noise.measurement_diagonal);  // eq. 7b
    out[i] = x;
  }
}

}  // namespace odocal
