#include "odocal/estimation/odometry_ekf.hpp"

#include <cmath>

#include "covariance_update.hpp"
#include "hot_loop.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/odometry_model.hpp"

namespace odocal {
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
  Pose2 x = reference.poses[0];
  Eigen::Matrix3d sigma = M;
  out[0] = x;
  OdometryJacobianPose F;
  StepwiseCosSin course_cos_sin;
  for (std::size_t i = 1; i < n; ++i) {
    if (wheels.breaks_at(reference.first_wheel_index + i)) {  // a gap: restart at the reference
      x = reference.poses[i];
      sigma = M;
      out[i] = x;
      continue;
    }
    const WheelIncrement increment = wheels.increment(reference.first_wheel_index + i);
    const BodyIncrement step = body_increment(increment, params);
    const CosSin course = course_cos_sin(x.z() + 0.5 * step.yaw_rad);
    x = predict_pose_on_course(x, increment, step, course, params, {.J_pose_pose = &F});  // eq. 5a
    sigma = propagate_heading_coupled(sigma, F(0, 2), F(1, 2), noise.process_diagonal);   // eq. 5b
    Eigen::Vector3d innovation = reference.poses[i] - x;                                  // eq. 7a
    innovation.z() = angle_difference(reference.poses[i].z(), x.z());
    const SymmetricInverse S_inverse = symmetric_inverse(sigma + M);
    const Eigen::Matrix3d sigma_adjugate = sigma.lazyProduct(S_inverse.adjugate);
    const Eigen::Matrix3d G = sigma_adjugate * S_inverse.inverse_det;  // eq. 8
    x += (sigma_adjugate * innovation) * S_inverse.inverse_det;
    sigma = joseph_update_identity_h(sigma, G, noise.measurement_diagonal);  // eq. 7b
    out[i] = x;
  }
}

}  // namespace odocal
