// BatchProblem's unknowns and its Ceres problem: built from the folds and pre-integrations of
// batch_problem_preintegration.cpp, solved, and read back (covariances, information criterion).
#include "batch_problem.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <utility>
#include <vector>

#include "batch_covariance.hpp"
#include "odocal/error.hpp"
#include "odocal/model/angle.hpp"

namespace odocal::batch {
namespace {

// Keyframes every interval_s, and on both sides of every break of the odometry chain (a wheel
// gap), so that the gap is a segment of its own, without odometry.
std::vector<std::size_t> keyframe_samples(const FittedWheels& wheels, std::size_t first,
                                          double interval_s) {
  std::vector<std::size_t> samples{first};
  for (std::size_t k = first + 1; k < wheels.size(); ++k) {
    if (wheels.breaks_at(k)) {
      if (samples.back() != k - 1) samples.push_back(k - 1);
      samples.push_back(k);
    } else if (wheels.t_s[k] - wheels.t_s[samples.back()] >= interval_s - 1e-9) {
      samples.push_back(k);
    }
  }
  if (samples.back() != wheels.size() - 1) samples.push_back(wheels.size() - 1);
  return samples;
}

double median_step_s(const std::vector<double>& t_s) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < t_s.size(); ++i) steps.push_back(t_s[i] - t_s[i - 1]);
  if (steps.empty()) return 0.0;
  std::nth_element(steps.begin(), steps.begin() + static_cast<long>(steps.size() / 2), steps.end());
  return steps[steps.size() / 2];
}

}  // namespace

BatchProblem::BatchProblem(const Log& log, FittedWheels wheels,
                           const ReferenceTrajectory& reference, const BatchOptions& options,
                           const CalibrationOptions& common, const OdometryParams& nominal)
    : log_(log),
      wheels_(wheels),
      sensors_(common.reference),
      batch_(options),
      body_(log.vehicle.body_geometry()),
      nominal_(nominal) {
  doppler_sigma_mps_ = options.doppler_sigma_mps(!log.gnss.speed_mps.empty());
  keyframes_ = keyframe_samples(wheels, reference.first_wheel_index, batch_.keyframe_interval_s);
  if (keyframes_.size() < 3) {
    throw InsufficientDataError(
        "too short for the batch calibration: fewer than 3 keyframes under GNSS");
  }
  for (const std::size_t k : keyframes_) {
    const Pose2& pose = reference.poses[k - reference.first_wheel_index];
    poses_.push_back({pose.x(), pose.y(), pose.z()});
  }
  start_poses_ = poses_;
  params_ = {nominal.circumference_rl_m, nominal.circumference_rr_m, nominal.track_width_m};
  lever_ = {batch_.lever_arm_x_m, batch_.lever_arm_y_m};
  latency_ = batch_.latency_s;
  if (batch_.tyre_model != TyreModelChoice::kNone || gentle_limits()) {
    // The driving state from the log at the nominal parameters: a per mille off in speed
    // moves a coefficient by as much, far inside its sigma.
    states_ = driving_states(wheels, imu(), nominal);
    TyreModel::Vector sum = TyreModel::Vector::Zero();
    for (std::size_t k = reference.first_wheel_index; k < states_.size(); ++k) {
      TyreModel::Vector x = tyre_regressors(states_[k], RearWheel::kLeft, body_);
      x(kSideSlipCoefficient) = side_slip_regressor(states_[k], body_);  // its effect in rad
      sum += x.cwiseAbs2();
    }
    const double n = static_cast<double>(states_.size() - reference.first_wheel_index);
    regressor_rms_ = (sum / std::max(n, 1.0)).cwiseSqrt();
  }
  mark_gentle_segments();
  gm_sigma_m_ = batch_.gnss_gauss_markov_sigma_m;
  const double gnss_step_s = median_step_s(log.gnss.t_s);
  speed_max_gap_s_ = std::max(3.0 * gnss_step_s, 0.5);
  if (gnss_step_s > 0.0)
    gnss_fixes_per_keyframe_ = std::max(1.0, batch_.keyframe_interval_s / gnss_step_s);
  gm_tau_s_ = batch_.gnss_gauss_markov_tau_s;
  gnss_bias_.assign(gauss_markov() ? keyframes_.size() : 0, Block2{0.0, 0.0});
  // Quantisation: the keyframes' counts are count-error states, the inner samples' counts are
  // in the segment covariance.
  quantisation_sigma_rev_ = batch_.quantisation_sigma_rev < 0.0
                                ? encoder_quantisation_sigma_rev(log)
                                : batch_.quantisation_sigma_rev;
  noise_ = {batch_.slip_sigma_m_per_sqrt_m, quantisation_sigma_rev_,
            batch_.lateral_sigma_m_per_sqrt_m};
  count_error_.assign(keyframes_.size(), Block2{0.0, 0.0});
  gnss_weights_.assign(log.gnss.size(), 1.0f);
  loss_.reset(gnss_loss());
}

void BatchProblem::set_tyre_terms(std::optional<TyreTerms> terms) {
  tyre_terms_ = terms;
  tyre_held_sigma_.fill(0.0);
  tyre_held_estimate_.fill(0.0);
  tyre_held_value_.fill(0.0);
  tyre_held_wandered_.fill(false);
  tyre_held_below_zero_.fill(false);
  std::fill(params_.begin() + kTyreOffset, params_.end(), 0.0);
}

void BatchProblem::hold_tyre_coefficient(int j, double sigma, FreeValue value) {
  const auto index = static_cast<std::size_t>(kTyreOffset + j);
  const auto held = static_cast<std::size_t>(j);
  tyre_held_sigma_[held] = sigma;
  tyre_held_wandered_[held] = value == FreeValue::kWandered;
  tyre_held_below_zero_[held] = value == FreeValue::kBelowZero;
  tyre_held_estimate_[held] = value == FreeValue::kWandered ? 0.0 : params_[index];
  tyre_held_value_[held] = 0.0;
  params_[index] = 0.0;
}

bool BatchProblem::hold_at_car_values() {
  bool moved = false;
  for (int j = 0; j < TyreModel::kCoefficients; ++j) {
    const auto held = static_cast<std::size_t>(j);
    if (!tyre_in_fit(j) || !tyre_held(j) || tyre_held_wandered_[held]) continue;
    const CarCoefficient car = car_coefficient(j);
    const CarCoefficient combined =
        combined_coefficient(tyre_held_estimate_[held], tyre_held_sigma_[held], car);
    // However far below zero the log put a slip that it did not identify.
    tyre_held_value_[held] =
        tyre_nonnegative(j) ? nonnegative_coefficient(combined).mean : combined.mean;
    moved = moved || tyre_held_value_[held] != 0.0;
  }
  return moved;
}

BatchProblem::Unknowns BatchProblem::unknowns(Folds folds) const {
  return {poses_,
          params_,
          lever_,
          latency_,
          heading_bias_,
          gyro_bias_,
          gnss_bias_,
          count_error_,
          folds == Folds::kRebuild ? std::optional(gnss_weights_) : std::nullopt};
}

void BatchProblem::set_unknowns(const Unknowns& u) {
  poses_ = u.poses;
  params_ = u.params;
  lever_ = u.lever;
  latency_ = u.latency;
  heading_bias_ = u.heading_bias;
  gyro_bias_ = u.gyro_bias;
  gnss_bias_ = u.gnss_bias;
  // A solution from under another GNSS noise model (a white one has no Gauss-Markov states):
  // the states start at zero. Left as they were, a white first estimate put back under an
  // adapted model had its folds point past the end of an empty vector, into the storage the
  // adapted solution's states had left behind.
  const std::size_t bias_states = gauss_markov() ? keyframes_.size() : 0;
  if (gnss_bias_.size() != bias_states) gnss_bias_.assign(bias_states, Block2{0.0, 0.0});
  count_error_ = u.count_error;
  if (u.gnss_weights) gnss_weights_ = *u.gnss_weights;
}

void BatchProblem::restart() {
  poses_ = start_poses_;
  params_ = {nominal_.circumference_rl_m, nominal_.circumference_rr_m, nominal_.track_width_m};
  std::copy(tyre_held_value_.begin(), tyre_held_value_.end(), params_.begin() + kTyreOffset);
  lever_ = {batch_.lever_arm_x_m, batch_.lever_arm_y_m};
  latency_ = batch_.latency_s;
  heading_bias_ = gyro_bias_ = 0.0;
  std::fill(gnss_bias_.begin(), gnss_bias_.end(), Block2{0.0, 0.0});
  std::fill(count_error_.begin(), count_error_.end(), Block2{0.0, 0.0});
  std::fill(gnss_weights_.begin(), gnss_weights_.end(), 1.0f);
  if (!states_.empty()) states_ = driving_states(wheels_, imu(), nominal_);
}

int BatchProblem::free_tyre_coefficients() const {
  int free = 0;
  for (int j = 0; j < TyreModel::kCoefficients; ++j) free += tyre_in_fit(j) && !tyre_held(j);
  return free;
}

bool BatchProblem::tyre_fit_wandered() const {
  for (int j = 0; j < TyreModel::kCoefficients; ++j)
    if (tyre_in_fit(j) && tyre_held_wandered_[static_cast<std::size_t>(j)]) return true;
  return false;
}

double BatchProblem::information_criterion(const ceres::Solver::Summary& solver) const {
  // The folded blocks' cost is the re-weighted one: the fixes' own (robust) cost and the
  // heading samples' replace it, and their rows count as the measurements they are.
  double folded_cost = 0.0, measured_cost = 0.0;
  for (const ceres::ResidualBlockId block : fold_blocks_) {
    double cost = 0.0;
    problem_->EvaluateResidualBlock(block, false, &cost, nullptr, nullptr);
    folded_cost += cost;
  }
  for_each_measurement(
      [&](std::size_t, std::size_t, const Eigen::Vector2d& whitened) {
        measured_cost += 0.5 * robust(whitened.squaredNorm())[0];
      },
      [&](std::size_t, double whitened) { measured_cost += 0.5 * whitened * whitened; });
  const double residuals = static_cast<double>(problem_->NumResiduals()) -
                           static_cast<double>(folded_rows_) +
                           static_cast<double>(measurement_rows_);
  return 2.0 * (solver.final_cost - folded_cost + measured_cost) +
         free_tyre_coefficients() * std::log(residuals);
}

void BatchProblem::set_gnss_noise(double white_scale, double gm_sigma_m, double gm_tau_s) {
  adapted_noise_ = true;
  white_scale_ = white_scale;
  gm_sigma_m_ = gm_sigma_m;
  gm_tau_s_ = gm_tau_s;
  gnss_bias_.assign(gauss_markov() ? keyframes_.size() : 0, Block2{0.0, 0.0});
}

void BatchProblem::build() {
  problem_ = std::make_unique<ceres::Problem>();
  folded_rows_ = 0;
  measurement_rows_ = 0;
  add_odometry();
  add_count_priors();
  add_folds();
  if (batch_.use_gyro && log_.imu) add_gyro();
  if (use_speed()) add_speed();
  if (gauss_markov()) add_gauss_markov();
  if (const double sigma_m = track_prior_sigma_m(); sigma_m > 0.0) {
    problem_->AddResidualBlock(
        new ceres::AutoDiffCostFunction<batch::TrackWidthPrior, 1, batch::kParams>(
            new batch::TrackWidthPrior{nominal_.track_width_m, sigma_m}),
        nullptr, params_.data());
  }
  hold_unrequested();
}

double BatchProblem::track_prior_sigma_m() const {
  if (!track_prior_ || batch_.estimate_track_width || tyre_terms_) return 0.0;
  return batch_.track_width_uncertainty * std::abs(nominal_.track_width_m);
}

ceres::Solver::Summary BatchProblem::solve(int max_iterations) {
  build();
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  // CHOLMOD (SuiteSparse) factors the normal equations without the permuted full copy that
  // Eigen's simplicial LDLT makes of them, in half its time per solve on the 2-hour urban drive
  // (docs/batch-calibration.md, "Memory and time").
  solver.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  solver.max_num_iterations = max_iterations > 0 ? max_iterations : batch_.max_solver_iterations;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  // Started from the layer-1 reference, the problem is nearly linear: Gauss-Newton steps are
  // good from the start (docs/batch-calibration.md).
  solver.initial_trust_region_radius = 1e8;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, problem_.get(), &summary);
  make_yaws_continuous();
  return summary;
}

void BatchProblem::make_yaws_continuous() {
  for (std::size_t i = 0; i + 1 < poses_.size() && i < odometry_.size(); ++i) {
    double turn = 0.0;
    if (!gap_segment(i) && rough_segment_[i] == 0) {
      turn = odometry_[i].residual.motion.delta(2);
    } else if (i < gyro_turns_.size() && gyro_turns_[i]) {
      turn = gyro_turns_[i]->integrated_rad;
    } else {
      continue;
    }
    const double change = poses_[i + 1][2] - poses_[i][2];
    // Only a whole turn moves a yaw: every other pose keeps its value to the bit.
    if (std::abs(change - turn) > std::numbers::pi)
      poses_[i + 1][2] = poses_[i][2] + turn + wrap_angle(change - turn);
  }
}

double BatchProblem::change_from(const Eigen::Ref<const batch::ParamsVector>& earlier) const {
  double change = 0.0;
  for (int p = 0; p < 3; ++p)
    change = std::max(change, std::abs(params_[p] - earlier(p)) / std::abs(earlier(p)));
  for (int j = 0; j < TyreModel::kCoefficients; ++j) {
    const int p = kTyreOffset + j;
    change = std::max(change, std::abs(params_[p] - earlier(p)) * regressor_rms_(j));
  }
  return change;
}

std::optional<BatchProblem::Uncertainty> BatchProblem::uncertainty() {
  const auto covariances = batch::marginal_covariances(*problem_, {{params_.data(), batch::kParams},
                                                                   {lever_.data(), 2},
                                                                   {&gyro_bias_, 1},
                                                                   {&heading_bias_, 1},
                                                                   {&latency_, 1}});
  if (!covariances) return std::nullopt;
  const std::vector<Eigen::MatrixXd>& c = *covariances;
  Uncertainty u;
  u.params = c[0];
  u.lever = c[1];
  u.gyro_bias = c[2](0, 0);
  u.heading_bias = c[3](0, 0);
  u.latency = c[4](0, 0);
  return u;
}

void BatchProblem::add_speed() {
  // The Doppler speed's outliers under the GNSS positions' loss (one per problem: it owns it).
  if (speed_intervals() == 0) return;
  ceres::LossFunction* loss = gnss_loss();
  for (std::size_t i = 0; i < speed_.size(); ++i) {
    if (!speed_[i]) continue;
    problem_->AddResidualBlock(
        new ceres::AutoDiffCostFunction<batch::SpeedResidual, 1, batch::kParams, 2, 1, 2, 2>(
            &*speed_[i], ceres::DO_NOT_TAKE_OWNERSHIP),
        loss, params_.data(), lever_.data(), &latency_, count_error_[i].data(),
        count_error_[i + 1].data());
  }
}

void BatchProblem::mark_gentle_segments() {
  rough_segment_.assign(keyframes_.size(), 0);
  if (!gentle_limits()) return;
  const auto over = [](double value, double limit) {
    return limit > 0.0 && std::abs(value) > limit;
  };
  for (std::size_t i = 0; i + 1 < keyframes_.size(); ++i) {
    for (std::size_t k = keyframes_[i] + 1; k <= keyframes_[i + 1]; ++k) {
      const DrivingState& s = states_[k];
      if (over(s.speed_mps, batch_.gentle_max_speed_mps) ||
          over(s.longitudinal_mps2, batch_.gentle_max_longitudinal_mps2) ||
          over(s.lateral_mps2(), batch_.gentle_max_lateral_mps2)) {
        rough_segment_[i] = 1;
        break;
      }
    }
  }
}

std::pair<std::size_t, std::size_t> BatchProblem::gentle_intervals() const {
  std::size_t used = 0;
  for (std::size_t i = 0; i + 1 < keyframes_.size(); ++i)
    used += (!gap_segment(i) && rough_segment_[i] == 0) ? 1 : 0;
  return {used, keyframes_.size() - 1};
}

void BatchProblem::add_odometry() {
  odometry_blocks_.clear();
  for (std::size_t i = 0; i < odometry_.size(); ++i) {
    if (gap_segment(i) || rough_segment_[i] != 0) continue;
    odometry_blocks_.push_back(
        {problem_->AddResidualBlock(new ceres::AutoDiffCostFunction<batch::OdometryResidual, 3, 3,
                                                                    3, batch::kParams, 2, 2>(
                                        &odometry_[i].residual, ceres::DO_NOT_TAKE_OWNERSHIP),
                                    nullptr, poses_[i].data(), poses_[i + 1].data(), params_.data(),
                                    count_error_[i].data(), count_error_[i + 1].data()),
         i});
  }
}

void BatchProblem::add_count_priors() {
  for (Block2& count : count_error_) {
    if (quantisation_sigma_rev_ > 0.0) {
      problem_->AddResidualBlock(new ceres::AutoDiffCostFunction<batch::CountErrorPrior, 2, 2>(
                                     new batch::CountErrorPrior{quantisation_sigma_rev_}),
                                 nullptr, count.data());
    } else {
      problem_->SetParameterBlockConstant(count.data());
    }
  }
}

ceres::LossFunction* BatchProblem::gnss_loss() const {
  switch (batch_.gnss_loss) {
    case RobustLoss::kHuber:
      return new ceres::HuberLoss(batch_.gnss_loss_scale);
    case RobustLoss::kCauchy:
      return new ceres::CauchyLoss(batch_.gnss_loss_scale);
    case RobustLoss::kNone:
      break;
  }
  return nullptr;
}

void BatchProblem::add_folds() {
  gnss_residuals_ = 0;
  fold_blocks_.clear();
  for (std::size_t i = 0; i < folds_.size(); ++i) {
    batch::FoldedIntervalResidual& fold = folds_[i];
    if (fold.factor.rows == 0) continue;
    double* bias = gauss_markov() ? gnss_bias_[i].data() : zero_bias_.data();
    fold_blocks_.push_back(problem_->AddResidualBlock(
        new ceres::AutoDiffCostFunction<batch::FoldedIntervalResidual, ceres::DYNAMIC, 3,
                                        batch::kParams, 2, 1, 2, 2, 1>(
            &fold, static_cast<int>(fold.factor.rows), ceres::DO_NOT_TAKE_OWNERSHIP),
        nullptr, poses_[i].data(), params_.data(), lever_.data(), &latency_, bias,
        count_error_[i].data(), &heading_bias_));
    folded_rows_ += static_cast<std::size_t>(fold.factor.rows);
  }
  gnss_residuals_ = folded_fixes_;
  measurement_rows_ += 2 * folded_fixes_ + folded_headings_;
  if (gnss_residuals_ == 0) {
    throw InsufficientDataError("no GNSS fix inside the wheel time span: nothing to fit");
  }
}

void BatchProblem::add_gyro() {
  gyro_turns_.assign(keyframes_.size(), std::nullopt);
  const ImuStream& imu = *log_.imu;
  const double step_s = median_step_s(imu.t_s);
  if (imu.size() < 2 || step_s <= 0.0) return;
  std::size_t j = 0;
  for (std::size_t i = 0; i + 1 < keyframes_.size(); ++i) {
    const double begin = wheels_.t_s[keyframes_[i]], end = wheels_.t_s[keyframes_[i + 1]];
    if (imu.t_s.front() > begin || imu.t_s.back() < end) continue;
    while (j + 1 < imu.size() && imu.t_s[j + 1] <= begin) ++j;
    double integrated = 0.0, largest_gap = 0.0;
    for (std::size_t m = j; m + 1 < imu.size() && imu.t_s[m] < end; ++m) {
      // The rate linear between samples (the trapezoid rule, as the driving state's means take
      // it). Held from each sample to the next instead, the turn lagged by half a sample: 10 ms
      // at 50 Hz biased the urban drive's circumferences by -4 mm (docs/batch-calibration.md,
      // "The gyro's turn over a keyframe interval").
      const double t0 = imu.t_s[m], t1 = imu.t_s[m + 1];
      const auto rate_at = [&](double t) {
        return imu.wz_radps[m] + (imu.wz_radps[m + 1] - imu.wz_radps[m]) * (t - t0) / (t1 - t0);
      };
      const double from = std::max(t0, begin), to = std::min(t1, end);
      integrated += 0.5 * (rate_at(from) + rate_at(to)) * (to - from);
      largest_gap = std::max(largest_gap, imu.t_s[m + 1] - imu.t_s[m]);
    }
    if (largest_gap > 5.0 * step_s) continue;  // an IMU dropout inside the interval
    const double duration = end - begin;
    auto* residual = new batch::GyroResidual{
        integrated, duration, sensors_.yaw_rate_sigma_radps * std::sqrt(step_s * duration)};
    gyro_turns_[i] = *residual;
    problem_->AddResidualBlock(
        new ceres::AutoDiffCostFunction<batch::GyroResidual, 1, 3, 3, 1>(residual), nullptr,
        poses_[i].data(), poses_[i + 1].data(), &gyro_bias_);
  }
}

void BatchProblem::add_gauss_markov() {
  const double sigma = gm_sigma_m_;
  problem_->AddResidualBlock(new ceres::AutoDiffCostFunction<batch::GaussMarkovPrior, 2, 2>(
                                 new batch::GaussMarkovPrior{sigma}),
                             nullptr, gnss_bias_[0].data());
  for (std::size_t i = 0; i + 1 < keyframes_.size(); ++i) {
    const double dt = wheels_.t_s[keyframes_[i + 1]] - wheels_.t_s[keyframes_[i]];
    const double phi = std::exp(-dt / gm_tau_s_);
    problem_->AddResidualBlock(
        new ceres::AutoDiffCostFunction<batch::GaussMarkovResidual, 2, 2, 2>(
            new batch::GaussMarkovResidual{phi, sigma * std::sqrt(1.0 - phi * phi)}),
        nullptr, gnss_bias_[i].data(), gnss_bias_[i + 1].data());
  }
}

void BatchProblem::hold_unrequested() {
  const auto hold = [&](double* block, bool estimate) {
    if (!estimate && problem_->HasParameterBlock(block)) problem_->SetParameterBlockConstant(block);
  };
  hold(zero_bias_.data(), false);
  hold(lever_.data(), batch_.estimate_lever_arm);
  hold(&latency_, batch_.estimate_latency);
  hold(&heading_bias_, batch_.estimate_heading_bias && use_heading());
  hold(&gyro_bias_, batch_.estimate_gyro_bias);
  std::vector<int> held;
  for (int p = 0; p < batch::kParams; ++p)
    if (!param_free(p)) held.push_back(p);
  if (!held.empty())
    problem_->SetManifold(params_.data(), new ceres::SubsetManifold(batch::kParams, held));
}

}  // namespace odocal::batch
