#include "odocal/estimation/odometry_preintegration.hpp"

#include <cmath>

#include "odocal/model/odometry_model.hpp"

namespace odocal {

PreintegratedSegment preintegrate(const FittedWheels& wheels, std::size_t first_sample,
                                  std::size_t last_sample, const OdometryParams& params,
                                  const WheelNoise& noise, const TyreConditions* tyre) {
  PreintegratedSegment segment;
  segment.first_sample = first_sample;
  segment.last_sample = last_sample;
  const std::size_t count = last_sample - first_sample + 1;
  segment.delta.resize(count, Pose2::Zero());
  segment.J_delta_params.resize(count, Eigen::Matrix3d::Zero());
  segment.J_delta_first_increment.resize(count, OdometryJacobianWheels::Zero());
  using TyreJacobian = Eigen::Matrix<double, 3, TyreModel::kCoefficients>;
  if (tyre != nullptr) {
    segment.J_delta_tyre.resize(count, TyreJacobian::Zero());
    segment.tyre_factors.resize(count);
  }
  const TyreModel::Vector k = tyre != nullptr ? tyre->model.coefficients() : TyreModel::Vector();
  OdometryJacobianPose F;
  OdometryJacobianWheels G = OdometryJacobianWheels::Zero();
  OdometryJacobianWheels G_previous = OdometryJacobianWheels::Zero();
  const double q2 = noise.quantisation_sigma_rev * noise.quantisation_sigma_rev;
  OdometryJacobianParams J_params;
  Eigen::Matrix3d& sigma = segment.covariance;
  const double slip_variance = noise.slip_sigma_m_per_sqrt_m * noise.slip_sigma_m_per_sqrt_m;
  for (std::size_t s = 1; s < count; ++s) {
    const WheelIncrement raw = wheels.increment(first_sample + s);
    WheelIncrement n = raw;
    TyreFactor factor_rl{}, factor_rr{};
    double side_slip = 0.0, side_slip_per_coefficient = 0.0;
    if (tyre != nullptr) {
      const DrivingState& state = tyre->states[first_sample + s];
      const RearTyreFactors factors =
          rear_tyre_factors_with_gradient(tyre->model, state, tyre->body);
      factor_rl = factors.left;
      factor_rr = factors.right;
      segment.tyre_factors[s] = {factor_rl, factor_rr};
      n.rev_rl *= factor_rl.value;
      n.rev_rr *= factor_rr.value;
      side_slip_per_coefficient = side_slip_regressor(state, tyre->body);
      side_slip = k(kSideSlipCoefficient) * side_slip_per_coefficient;
    }
    OdometryJacobianSideSlip J_side_slip;
    segment.delta[s] = predict_pose(segment.delta[s - 1], n, params, side_slip,
                                    {.J_pose_pose = &F,
                                     .J_pose_wheels = &G,
                                     .J_pose_params = &J_params,
                                     .J_pose_side_slip = tyre != nullptr ? &J_side_slip : nullptr});
    segment.J_delta_params[s] = F * segment.J_delta_params[s - 1] + J_params;
    if (tyre != nullptr) {
      Eigen::Matrix<double, 2, TyreModel::kCoefficients> J_increment_tyre;
      J_increment_tyre.row(0) = raw.rev_rl * factor_rl.gradient.transpose();
      J_increment_tyre.row(1) = raw.rev_rr * factor_rr.gradient.transpose();
      segment.J_delta_tyre[s] = F * segment.J_delta_tyre[s - 1] + G * J_increment_tyre;
      segment.J_delta_tyre[s].col(kSideSlipCoefficient) += J_side_slip * side_slip_per_coefficient;
      // The count errors are errors of the raw counts: they carry the factors too.
      if (raw.rev_rl != 0.0) G.col(0) *= n.rev_rl / raw.rev_rl;
      if (raw.rev_rr != 0.0) G.col(1) *= n.rev_rr / raw.rev_rr;
    }
    // Slip variance in revolutions^2: slip^2 |arc| / c^2.
    const Eigen::Vector2d wheel_variance(
        slip_variance * std::abs(n.rev_rl) / params.circumference_rl_m,
        slip_variance * std::abs(n.rev_rr) / params.circumference_rr_m);
    sigma = F * sigma * F.transpose() + G * wheel_variance.asDiagonal() * G.transpose();
    if (s >= 2) {
      // The count at inner sample s - 1 is off by e: +e in the previous increment, -e in this one.
      // Its heading blip moves everything after it sideways; summed over a segment, a random walk.
      const OdometryJacobianWheels inner = F * G_previous - G;
      sigma += q2 * inner * inner.transpose();
    }
    G_previous = G;
    const double course = 0.5 * (segment.delta[s - 1].z() + segment.delta[s].z());
    const Eigen::Vector2d across(-std::sin(course), std::cos(course));
    const double step_m = (segment.delta[s].head<2>() - segment.delta[s - 1].head<2>()).norm();
    const double lateral = noise.lateral_sigma_m_per_sqrt_m;
    sigma.topLeftCorner<2, 2>() += lateral * lateral * step_m * across * across.transpose();
    segment.J_delta_first_increment[s] =
        s == 1 ? G : (F * segment.J_delta_first_increment[s - 1]).eval();
  }
  segment.J_end_last_increment = G;
  return segment;
}

}  // namespace odocal
