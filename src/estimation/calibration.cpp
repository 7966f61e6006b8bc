#include "odocal/estimation/calibration.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "batch_calibration.hpp"
#include "hot_loop.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/circumference_ls.hpp"
#include "odocal/estimation/dead_reckoning.hpp"
#include "odocal/estimation/odometry_ekf.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/path_length.hpp"

namespace odocal {
namespace {

// Dead reckoning of the whole log with given parameters, compared with the reference
// (section 4: "the two-wheel vehicle model with the new parameters is simulated on the whole
// dataset"). The start pose follows options.dr_start. Both live on the wheel time base, so the
// comparison is index by index; the buffers are allocated once.
class WholeLogEvaluator {
 public:
  WholeLogEvaluator(const WheelStream& wheels, const ReferenceTrajectory& reference,
                    const CalibrationOptions& options)
      : wheels_(wheels), reference_(reference), options_(options), path_(reference.poses.size()) {
    const double window_end = reference.poses.t_s.front() + options.dr_align_window_s;
    align_count_ =
        options.dr_start == DeadReckoningStart::kAlignedWhole
            ? reference.poses.size()
            : static_cast<std::size_t>(std::upper_bound(reference.poses.t_s.begin(),
                                                        reference.poses.t_s.end(), window_end) -
                                       reference.poses.t_s.begin());
    source_.resize(2, static_cast<Eigen::Index>(align_count_));
    target_.resize(2, static_cast<Eigen::Index>(align_count_));
    for (std::size_t i = 0; i < align_count_; ++i) {
      target_.col(static_cast<Eigen::Index>(i)) = reference.poses.pose[i].head<2>();
    }
  }

  ODOCAL_HOT_LOOP DeadReckoningSummary evaluate(const OdometryParams& params) {
    path_[0] = reference_.poses.pose[0];
    dead_reckon_into(wheels_, reference_.first_wheel_index, params, path_);
    if (options_.dr_start != DeadReckoningStart::kFirstReference && align_count_ >= 2)
      align_start();
    DeadReckoningSummary summary;
    for (std::size_t i = 0; i < path_.size(); ++i) {
      const Pose2& reference = reference_.poses.pose[i];
      const double position_m = (path_[i].head<2>() - reference.head<2>()).norm();
      const double heading_rad = std::abs(angle_difference(path_[i].z(), reference.z()));
      summary.mean_position_m += position_m;
      summary.mean_heading_rad += heading_rad;
      summary.max_position_m = std::max(summary.max_position_m, position_m);
      summary.max_heading_rad = std::max(summary.max_heading_rad, heading_rad);
    }
    summary.mean_position_m /= static_cast<double>(path_.size());
    summary.mean_heading_rad /= static_cast<double>(path_.size());
    return summary;
  }

  double distance_m(const OdometryParams& params) {
    path_[0] = Pose2::Zero();
    dead_reckon_into(wheels_, reference_.first_wheel_index, params, path_);
    return path_length_m(path_);
  }

 private:
  // Moves the whole path rigidly so that its first align_count_ positions best fit the reference.
  void align_start() {
    for (std::size_t i = 0; i < align_count_; ++i)
      source_.col(static_cast<Eigen::Index>(i)) = path_[i].head<2>();
    const Eigen::Matrix3d T = Eigen::umeyama(source_, target_, false);
    const double rotation = std::atan2(T(1, 0), T(0, 0));
    for (Pose2& pose : path_) {
      pose.head<2>() = T.topLeftCorner<2, 2>() * pose.head<2>() + T.topRightCorner<2, 1>();
      pose.z() += rotation;
    }
  }

  const WheelStream& wheels_;
  const ReferenceTrajectory& reference_;
  const CalibrationOptions& options_;
  std::vector<Pose2> path_;
  Eigen::Matrix2Xd source_, target_;
  std::size_t align_count_{};
};

void require_identifiable_fit(const CircumferenceFit& fit, const CalibrationOptions& options) {
  if (!std::isfinite(fit.condition_number) || fit.condition_number > options.max_condition_number ||
      !fit.circumference_m.allFinite()) {
    throw InsufficientDataError(
        fmt::format("the least-squares problem cannot separate c_RL and c_RR (condition number "
                    "{:.3g} > {:.3g}): "
                    "the log needs more distance and more turning",
                    fit.condition_number, options.max_condition_number));
  }
}

void run_iterative(const Log& log, const ReferenceTrajectory& reference,
                   WholeLogEvaluator& evaluator, const CalibrationOptions& options,
                   CalibrationResult& result) {
  OdometryParams params = result.nominal;
  std::vector<Pose2> x_hat;
  double best_score = std::numeric_limits<double>::infinity();
  int since_best = 0;
  CircumferenceFit best_fit;
  for (int i = 1; i <= options.max_iterations; ++i) {
    const OdometryEkfNoise noise{options.method == CalibrationMethod::kIterative
                                     ? decaying_process_diagonal(i, options.decay_exponent_q)
                                     : options.fixed_process_diagonal,
                                 options.measurement_diagonal};
    run_odometry_ekf(log.wheels, reference, params, noise, x_hat);
    const CircumferenceFit fit =
        result.difference_identifiable
            ? fit_circumferences(log.wheels, reference, x_hat, params.track_width_m,
                                 options.ls_weights, options.ls_window_samples)
            : fit_common_scale(log.wheels, reference, x_hat, params.track_width_m,
                               options.ls_weights, options.ls_window_samples,
                               Eigen::Vector2d(result.nominal.circumference_rl_m,
                                               result.nominal.circumference_rr_m));
    require_identifiable_fit(fit, options);
    params.circumference_rl_m = fit.circumference_m(0);
    params.circumference_rr_m = fit.circumference_m(1);
    IterationRecord record{i, params.circumference_rl_m, params.circumference_rr_m,
                           evaluator.evaluate(params), 0.0};
    record.score = record.errors.mean_position_m +
                   options.heading_weight_m_per_rad * record.errors.mean_heading_rad;
    result.iterations.push_back(record);
    if (record.score < best_score) {
      best_score = record.score;
      since_best = 0;
      best_fit = fit;
      result.chosen_iteration = i;
    } else if (++since_best >= options.patience) {
      result.termination = fmt::format(
          "minimum of the dead-reckoning errors at iteration {}; stopped after {} iterations "
          "without a new minimum",
          result.chosen_iteration, options.patience);
      break;
    }
  }
  if (result.termination.empty()) {
    result.termination =
        fmt::format("reached {} iterations; minimum of the dead-reckoning errors at iteration {}",
                    options.max_iterations, result.chosen_iteration);
  }
  const IterationRecord& chosen =
      result.iterations[static_cast<std::size_t>(result.chosen_iteration - 1)];
  result.estimate.circumference_rl_m = chosen.circumference_rl_m;
  result.estimate.circumference_rr_m = chosen.circumference_rr_m;
  result.covariance = best_fit.covariance;
  result.condition_number = best_fit.condition_number;
}

void run_augmented(const Log& log, const ReferenceTrajectory& reference,
                   const CalibrationOptions& options, CalibrationResult& result) {
  using Vector5 = Eigen::Matrix<double, 5, 1>;
  using Matrix5 = Eigen::Matrix<double, 5, 5>;
  Vector5 x;
  x << reference.poses.pose[0], result.nominal.circumference_rl_m,
      result.nominal.circumference_rr_m;
  Matrix5 sigma = Matrix5::Zero();
  sigma.topLeftCorner<3, 3>() = options.measurement_diagonal.asDiagonal();
  sigma(3, 3) = sigma(4, 4) =
      options.augmented_initial_param_sigma_m * options.augmented_initial_param_sigma_m;
  Matrix5 Q = Matrix5::Zero();
  Q.topLeftCorner<3, 3>() = options.augmented_pose_process_diagonal.asDiagonal();
  Q(3, 3) = Q(4, 4) =
      options.augmented_param_sigma_m_per_step * options.augmented_param_sigma_m_per_step;
  const Eigen::Matrix3d M = options.measurement_diagonal.asDiagonal();
  const std::size_t n = reference.poses.size();
  result.parameter_t_s.reserve(n);
  result.parameter_c_rl_m.reserve(n);
  result.parameter_c_rr_m.reserve(n);
  OdometryJacobianPose J_pose;
  OdometryJacobianParams J_params;
  for (std::size_t i = 1; i < n; ++i) {
    const OdometryParams params{x(3), x(4), result.nominal.track_width_m};
    const Pose2 predicted =
        predict_pose(x.head<3>(), log.wheels.increment(reference.first_wheel_index + i), params,
                     0.0, {.J_pose_pose = &J_pose, .J_pose_params = &J_params});
    Matrix5 F = Matrix5::Identity();
    F.topLeftCorner<3, 3>() = J_pose;
    F.block<3, 2>(0, 3) = J_params.leftCols<2>();
    x.head<3>() = predicted;
    sigma = F * sigma * F.transpose() + Q;
    Eigen::Vector3d innovation = reference.poses.pose[i] - predicted;
    innovation.z() = angle_difference(reference.poses.pose[i].z(), predicted.z());
    const Eigen::Matrix3d S = sigma.topLeftCorner<3, 3>() + M;
    const Eigen::LLT<Eigen::Matrix3d> S_llt(S);
    const Eigen::Matrix<double, 5, 3> K = S_llt.solve(sigma.topRows<3>()).transpose();
    x += K * innovation;
    Matrix5 I_KH = Matrix5::Identity();
    I_KH.leftCols<3>() -= K;
    sigma = I_KH * sigma * I_KH.transpose() + K * M * K.transpose();
    sigma = 0.5 * (sigma + sigma.transpose());
    result.parameter_t_s.push_back(reference.poses.t_s[i]);
    result.parameter_c_rl_m.push_back(x(3));
    result.parameter_c_rr_m.push_back(x(4));
  }
  result.estimate.circumference_rl_m = x(3);
  result.estimate.circumference_rr_m = x(4);
  result.covariance = sigma.bottomRightCorner<2, 2>();
  if (!result.difference_identifiable) {  // keep only the common scale of the two estimates
    const Eigen::Vector2d nominal(result.nominal.circumference_rl_m,
                                  result.nominal.circumference_rr_m);
    const Eigen::Vector2d weights = nominal.cwiseInverse() / 2.0;
    const double scale = weights.dot(x.tail<2>());
    result.estimate.circumference_rl_m = scale * nominal(0);
    result.estimate.circumference_rr_m = scale * nominal(1);
    result.covariance = weights.dot(result.covariance * weights) * nominal * nominal.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(result.covariance);
  result.condition_number = std::sqrt(eigen.eigenvalues()(1) / eigen.eigenvalues()(0));
  result.termination = "augmented Kalman filter: final estimate after the last sample";
}

}  // namespace

const char* method_name(CalibrationMethod method) {
  switch (method) {
    case CalibrationMethod::kIterative:
      return "iterative";
    case CalibrationMethod::kFixedP:
      return "fixed-p";
    case CalibrationMethod::kAugmented:
      return "augmented";
    case CalibrationMethod::kBatch:
      return "batch";
  }
  return "iterative";
}

std::string CalibrationOptions::validate() const {
  if (decay_exponent_q < 1.0 || decay_exponent_q > 2.0)
    return "decay_exponent_q must lie in [1, 2] (paper eq. 13)";
  if ((measurement_diagonal.array() <= 0).any()) return "measurement covariance M must be positive";
  if ((fixed_process_diagonal.array() <= 0).any())
    return "fixed process covariance P must be positive";
  if ((ls_weights.array() <= 0).any()) return "least-squares weights W must be positive";
  if (max_iterations < 1) return "max_iterations must be at least 1";
  if (ls_window_samples < 1) return "ls_window_samples must be at least 1";
  if (min_heading_range_for_difference_rad < 0)
    return "min_heading_range_for_difference_rad must not be negative";
  if (patience < 1) return "patience must be at least 1";
  if (heading_weight_m_per_rad < 0) return "heading_weight_m_per_rad must not be negative";
  if ((augmented_pose_process_diagonal.array() <= 0).any() ||
      augmented_param_sigma_m_per_step < 0 || augmented_initial_param_sigma_m <= 0) {
    return "augmented Kalman filter noise must be positive";
  }
  return "";
}

CalibrationResult calibrate(const Log& log, const CalibrationOptions& options) {
  if (const std::string problem = options.validate(); !problem.empty())
    throw Error("invalid calibration options: " + problem);
  const ReferenceTrajectory reference = compute_reference(log, options.reference);
  if (reference.poses.size() < options.min_reference_samples) {
    throw InsufficientDataError(
        fmt::format("too short: the reference covers {} wheel samples, at least {} are needed",
                    reference.poses.size(), options.min_reference_samples));
  }
  CalibrationResult result;
  result.method = options.method;
  result.nominal = log.vehicle.nominal_params();
  result.estimate = result.nominal;
  result.reference_samples = reference.poses.size();
  result.reference_heading_source = reference.heading_source;
  WholeLogEvaluator evaluator(log.wheels, reference, options);
  result.distance_m = evaluator.distance_m(result.nominal);
  if (result.distance_m < options.min_distance_m) {
    throw InsufficientDataError(fmt::format(
        "the vehicle barely moves: {:.1f} m of wheel odometry, at least {} m are needed",
        result.distance_m, options.min_distance_m));
  }
  double lowest = reference.poses.pose[0].z(), highest = lowest;
  for (const Pose2& pose : reference.poses.pose) {
    lowest = std::min(lowest, pose.z());
    highest = std::max(highest, pose.z());
  }
  result.difference_identifiable = highest - lowest >= options.min_heading_range_for_difference_rad;
  result.identifiability =
      result.difference_identifiable
          ? fmt::format("c_RL and c_RR identified separately (heading range {:.0f} deg)",
                        deg_from_rad(highest - lowest))
          : fmt::format(
                "the left/right difference is not identifiable: the heading only spans {:.1f} deg "
                "(needs {:.0f} "
                "deg of turning to tell it from a gyro or heading bias); only the common scale of "
                "the nominal "
                "circumferences was estimated",
                deg_from_rad(highest - lowest),
                deg_from_rad(options.min_heading_range_for_difference_rad));
  result.before = evaluator.evaluate(result.nominal);
  if (options.method == CalibrationMethod::kAugmented) {
    run_augmented(log, reference, options, result);
  } else if (options.method == CalibrationMethod::kBatch) {
    run_batch(log, reference, options, result);
  } else {
    run_iterative(log, reference, evaluator, options, result);
  }
  result.after = evaluator.evaluate(result.estimate);
  return result;
}

}  // namespace odocal
