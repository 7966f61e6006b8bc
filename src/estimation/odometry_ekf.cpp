#include "odocal/estimation/odometry_ekf.hpp"

#include <Eigen/LU>
#include <cmath>

#include "odocal/model/angle.hpp"

namespace odocal {

Eigen::Vector3d decaying_process_diagonal(int iteration, double q) {
  const double scale = 1.0 / std::pow(static_cast<double>(iteration), q);
  return Eigen::Vector3d(150.0, 150.0, 15.0) * scale;
}

void run_odometry_ekf(const WheelStream& wheels, const ReferenceTrajectory& reference,
                      const OdometryParams& params, const OdometryEkfNoise& noise,
                      std::vector<Pose2>& out) {
  const std::size_t n = reference.poses.size();
  out.resize(n);
  const Eigen::Matrix3d P = noise.process_diagonal.asDiagonal();
  const Eigen::Matrix3d M = noise.measurement_diagonal.asDiagonal();
  Pose2 x = reference.poses.pose[0];
  Eigen::Matrix3d sigma = M;
  out[0] = x;
  OdometryJacobianPose F;
  for (std::size_t i = 1; i < n; ++i) {
    const std::size_t k = reference.first_wheel_index + i;
    x = predict_pose(x, wheels.increment(k), params, 0.0, {.J_pose_pose = &F});  // eq. 5a
    sigma = F.lazyProduct(sigma).lazyProduct(F.transpose()) + P;                 // eq. 5b
    Eigen::Vector3d innovation = reference.poses.pose[i] - x;                    // eq. 7a
    innovation.z() = angle_difference(reference.poses.pose[i].z(), x.z());
    // S >= M is positive definite and well conditioned, so Eigen's closed-form 3x3 inverse is
    // as accurate here as a Cholesky solve and several times faster (no dynamic-size kernels).
    const Eigen::Matrix3d S_inverse = (sigma + M).inverse();
    const Eigen::Matrix3d G = sigma.lazyProduct(S_inverse);  // eq. 8
    x += G * innovation;
    const Eigen::Matrix3d I_G = Eigen::Matrix3d::Identity() - G;  // Joseph form of eq. 7b
    const Eigen::Matrix3d I_G_sigma = I_G.lazyProduct(sigma);
    const Eigen::Matrix3d G_M = G * M.diagonal().asDiagonal();
    sigma = I_G_sigma.lazyProduct(I_G.transpose()) + G_M.lazyProduct(G.transpose());
    sigma = 0.5 * (sigma + sigma.transpose());
    out[i] = x;
  }
}

}  // namespace odocal
