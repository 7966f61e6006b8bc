#include "odocal/estimation/augmented_calibration.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>

#include "calibration_report.hpp"
#include "calibration_run.hpp"
#include "covariance_update.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/odometry_model.hpp"

namespace odocal {
namespace {

using Vector5 = Eigen::Matrix<double, 5, 1>;
using Matrix5 = Eigen::Matrix<double, 5, 5>;

void run_filter(const Log& log, const ReferenceTrajectory& reference,
                const AugmentedOptions& options, const CalibrationOptions& common,
                AugmentedSummary& summary) {
  Vector5 x;
  x << reference.poses[0], summary.nominal.circumference_rl_m, summary.nominal.circumference_rr_m;
  Matrix5 sigma = Matrix5::Zero();
  sigma.topLeftCorner<3, 3>() = common.measurement_diagonal.asDiagonal();
  sigma(3, 3) = sigma(4, 4) = options.initial_param_sigma_m * options.initial_param_sigma_m;
  Matrix5 Q = Matrix5::Zero();
  Q.topLeftCorner<3, 3>() = options.pose_process_diagonal.asDiagonal();
  Q(3, 3) = Q(4, 4) = options.param_sigma_m_per_step * options.param_sigma_m_per_step;
  const Eigen::Matrix3d M = common.measurement_diagonal.asDiagonal();
  const std::size_t n = reference.poses.size();
  const std::span<const double> t = reference.times(log.wheels);
  summary.parameter_t_s.reserve(n);
  summary.parameter_c_rl_m.reserve(n);
  summary.parameter_c_rr_m.reserve(n);
  OdometryJacobianPose J_pose;
  OdometryJacobianParams J_params;
  Eigen::Matrix<double, 3, 5> H = Eigen::Matrix<double, 3, 5>::Zero();  // the pose is measured
  H.leftCols<3>().setIdentity();
  for (std::size_t i = 1; i < n; ++i) {
    summary.parameter_t_s.push_back(t[i]);
    if (log.wheels.breaks_at(reference.first_wheel_index + i)) {
      // A wheel gap: the pose restarts at the reference, the parameters keep what they learnt.
      x.head<3>() = reference.poses[i];
      sigma.topLeftCorner<3, 3>() = M;
      sigma.topRightCorner<3, 2>().setZero();
      sigma.bottomLeftCorner<2, 3>().setZero();
      summary.parameter_c_rl_m.push_back(x(3));
      summary.parameter_c_rr_m.push_back(x(4));
      continue;
    }
    const OdometryParams params{x(3), x(4), summary.nominal.track_width_m};
    const Pose2 predicted =
        predict_pose(x.head<3>(), log.wheels.increment(reference.first_wheel_index + i), params,
                     0.0, {.J_pose_pose = &J_pose, .J_pose_params = &J_params});
    Matrix5 F = Matrix5::Identity();
    F.topLeftCorner<3, 3>() = J_pose;
    F.block<3, 2>(0, 3) = J_params.leftCols<2>();
    x.head<3>() = predicted;
    sigma = F * sigma * F.transpose() + Q;
    Eigen::Vector3d innovation = reference.poses[i] - predicted;
    innovation.z() = angle_difference(reference.poses[i].z(), predicted.z());
    const Eigen::Matrix3d S = sigma.topLeftCorner<3, 3>() + M;
    const Eigen::LLT<Eigen::Matrix3d> S_llt(S);
    const Eigen::Matrix<double, 5, 3> K = S_llt.solve(sigma.topRows<3>()).transpose();
    x += K * innovation;
    sigma = joseph_update(sigma, K, H, M);
    summary.parameter_c_rl_m.push_back(x(3));
    summary.parameter_c_rr_m.push_back(x(4));
  }
  summary.estimate.circumference_rl_m = x(3);
  summary.estimate.circumference_rr_m = x(4);
  summary.covariance = sigma.bottomRightCorner<2, 2>();
  if (!summary.difference_identifiable) {  // keep only the common scale of the two estimates
    const Eigen::Vector2d nominal(summary.nominal.circumference_rl_m,
                                  summary.nominal.circumference_rr_m);
    const Eigen::Vector2d weights = nominal.cwiseInverse() / 2.0;
    const double scale = weights.dot(x.tail<2>());
    summary.estimate.circumference_rl_m = scale * nominal(0);
    summary.estimate.circumference_rr_m = scale * nominal(1);
    summary.covariance = weights.dot(summary.covariance * weights) * nominal * nominal.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(summary.covariance);
  summary.condition_number = std::sqrt(eigen.eigenvalues()(1) / eigen.eigenvalues()(0));
  summary.message = "augmented Kalman filter: final estimate after the last sample";
}

}  // namespace

OptionTable<AugmentedOptions> AugmentedOptions::fields() {
  using O = AugmentedOptions;
  static const std::array<OptionField<O>, 3> kFields{{
      {"pose_process_diagonal", "[m^2, m^2, rad^2]", 1e-12, 1e12, "pose process noise per step",
       &O::pose_process_diagonal},
      {"param_sigma_m_per_step", "m", 0.0, 1.0, "random walk of each circumference per step",
       &O::param_sigma_m_per_step},
      {"initial_param_sigma_m", "m", 1e-9, 1.0, "initial 1-sigma of each circumference",
       &O::initial_param_sigma_m},
  }};
  return kFields;
}

std::string AugmentedOptions::validate() const { return check_option_ranges(fields(), *this); }

std::string AugmentedSummary::full_report() const {
  std::string text = report_heading(*this);
  if (!difference_identifiable) text += fmt::format("{:<13}{}\n", "note", identifiability);
  return text + report_ending(*this);
}

AugmentedSummary calibrate_augmented(const Log& log, const AugmentedOptions& options,
                                     const CalibrationOptions& common) {
  require_valid("augmented", options.validate());
  AugmentedSummary summary;
  CalibrationRun run(log, common, CalibrationMethod::kAugmented, summary);
  run_filter(run.log(), run.reference(), options, common, summary);
  run.finish(summary);
  return summary;
}

}  // namespace odocal
