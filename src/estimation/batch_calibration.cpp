#include "odocal/estimation/batch_calibration.hpp"

#include <ceres/ceres.h>
#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <tuple>
#include <type_traits>
#include <utility>

#include "batch_covariance.hpp"
#include "batch_fit.hpp"
#include "batch_folded_residuals.hpp"
#include "batch_observability.hpp"
#include "batch_refusal.hpp"
#include "batch_residuals.hpp"
#include "batch_speed_residual.hpp"
#include "calibration_report.hpp"
#include "calibration_run.hpp"
#include "doppler_scale.hpp"
#include "gnss_noise_estimate.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/estimation/odometry_preintegration.hpp"
#include "odocal/model/tyre_car_prior.hpp"

namespace odocal {
namespace {

using Block3 = std::array<double, 3>;

// What vehicle.yaml's body is taken to be uncertain by (1 sigma): a data sheet's numbers for a
// car as it is loaded and tyred on the day (docs/tyre-model.md).
struct BodyUncertainty {
  const char* key;  // vehicle.yaml's
  double VehicleBody::*member;
  double absolute;  // sigma = absolute + relative * value
  double relative;
  double sigma(const VehicleBody& body) const { return absolute + relative * (body.*member); }
  std::string text() const {
    return absolute > 0.0 ? fmt::format("{} +-{:g}", key, absolute)
                          : fmt::format("{} +-{:g} %", key, 100.0 * relative);
  }
};
constexpr BodyUncertainty kBodyUncertainties[] = {
    {"rear_axle_load_share", &VehicleBody::rear_axle_load_share, 0.04, 0.0},
    {"cg_height_m", &VehicleBody::cg_height_m, 0.1, 0.0},
    {"rear_roll_share", &VehicleBody::rear_roll_share, 0.1, 0.0},
    {"drag_area_m2", &VehicleBody::drag_area_m2, 0.0, 0.3},
    {"rolling_resistance", &VehicleBody::rolling_resistance, 0.004, 0.0},
};
using Block2 = std::array<double, 2>;
using ParamsBlock = std::array<double, batch::kParams>;  // [c_RL, c_RR, t_R, tyre coefficients]
constexpr int kTyreOffset = 3;

// The segment's Jacobian at sample s with respect to every parameter.
batch::ParamsJacobian params_jacobian(const PreintegratedSegment& segment, std::size_t s) {
  batch::ParamsJacobian J = batch::ParamsJacobian::Zero();
  J.leftCols<3>() = segment.J_delta_params[s];
  if (!segment.J_delta_tyre.empty())
    J.rightCols<TyreModel::kCoefficients>() = segment.J_delta_tyre[s];
  return J;
}

// Keyframes every interval_s, and on both sides of every break of the odometry chain (a wheel
// gap), so that the gap is a segment of its own, without odometry.
std::vector<std::size_t> keyframe_samples(const WheelStream& wheels, std::size_t first,
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

// The mean of a per-sample column over the increments of samples (from, to].
double interval_mean(const std::vector<float>& column, std::size_t from, std::size_t to) {
  double sum = 0.0;
  for (std::size_t k = from + 1; k <= to; ++k) sum += column[k];
  return to > from ? sum / static_cast<double>(to - from) : column[from];
}

double median_step_s(const std::vector<double>& t_s) {
  std::vector<double> steps;
  for (std::size_t i = 1; i < t_s.size(); ++i) steps.push_back(t_s[i] - t_s[i - 1]);
  if (steps.empty()) return 0.0;
  std::nth_element(steps.begin(), steps.begin() + static_cast<long>(steps.size() / 2), steps.end());
  return steps[steps.size() / 2];
}

// The batch problem: its unknowns live here across re-linearisations; each build() makes a fresh
// Ceres problem around the current pre-integration.
class BatchProblem {
 public:
  BatchProblem(const Log& log, const ReferenceTrajectory& reference, const BatchOptions& options,
               const CalibrationOptions& common, const OdometryParams& nominal)
      : log_(log),
        sensors_(common.reference),
        batch_(options),
        body_(log.vehicle.body_geometry()),
        nominal_(nominal) {
    doppler_sigma_mps_ = options.doppler_sigma_mps(!log.gnss.speed_mps.empty());
    keyframes_ =
        keyframe_samples(log.wheels, reference.first_wheel_index, batch_.keyframe_interval_s);
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
    if (batch_.tyre_model != TyreModelChoice::kNone || gentle_limits()) {
      // The driving state from the log at the nominal parameters: a per mille off in speed
      // moves a coefficient by as much, far inside its sigma.
      states_ = driving_states(log, nominal);
      TyreModel::Vector sum = TyreModel::Vector::Zero();
      for (std::size_t k = reference.first_wheel_index; k < states_.size(); ++k) {
        TyreModel::Vector x = tyre_regressors(states_[k], RearWheel::kLeft, body_);
        x(kSideSlipCoefficient) = side_slip_regressor(states_[k]);  // its effect in rad
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
  // The folds and the problem point into the object's own members: it stays where it was built.
  BatchProblem(const BatchProblem&) = delete;
  BatchProblem& operator=(const BatchProblem&) = delete;

  bool gauss_markov() const { return gm_sigma_m_ > 0.0; }

  // Fits the tyre model's terms of one family from here on (none: the plain model), every
  // coefficient back at zero.
  void set_tyre_terms(std::optional<TyreTerms> terms) {
    tyre_terms_ = terms;
    tyre_held_sigma_.fill(0.0);
    tyre_held_estimate_.fill(0.0);
    tyre_held_value_.fill(0.0);
    tyre_held_wandered_.fill(false);
    std::fill(params_.begin() + kTyreOffset, params_.end(), 0.0);
  }
  bool tyre_fitted() const { return tyre_terms_.has_value(); }
  std::optional<TyreTerms> tyre_terms() const { return tyre_terms_; }
  // Whether coefficient j belongs to the family being fitted (held at zero or free).
  bool tyre_in_fit(int j) const {
    return tyre_terms_ && kTyreCoefficients[static_cast<std::size_t>(j)].terms == *tyre_terms_;
  }
  // Holds coefficient j at zero from the next solve on (hold_at_car_values may move it after the
  // decisions): the log cannot identify it. Its sigma when it was free is kept for the report,
  // and with its value there for where it is held and its share of the circumferences' sigma; a
  // fit that wandered says nothing of the value.
  enum class FreeValue { kEstimate, kWandered };
  void hold_tyre_coefficient(int j, double sigma, FreeValue value = FreeValue::kEstimate) {
    const auto index = static_cast<std::size_t>(kTyreOffset + j);
    const auto held = static_cast<std::size_t>(j);
    tyre_held_sigma_[held] = sigma;
    tyre_held_wandered_[held] = value == FreeValue::kWandered;
    tyre_held_estimate_[held] = value == FreeValue::kEstimate ? params_[index] : 0.0;
    tyre_held_value_[held] = 0.0;
    params_[index] = 0.0;
  }
  // Moves every held physical coefficient from zero to where a car's value of it and what the
  // log said while it was free put it together (tyre_car_prior.hpp), for the next solve on;
  // whether any moved. Not where the fit wandered: a log whose fit does not settle is no car's
  // tyre (the Husky robot).
  bool hold_at_car_values() {
    bool moved = false;
    for (int j = 0; j < TyreModel::kCoefficients; ++j) {
      const auto held = static_cast<std::size_t>(j);
      if (!tyre_in_fit(j) || !tyre_held(j) || tyre_held_wandered_[held]) continue;
      tyre_held_value_[held] = combined_coefficient(tyre_held_estimate_[held],
                                                    tyre_held_sigma_[held], car_coefficient(j))
                                   .mean;
      moved = moved || tyre_held_value_[held] != 0.0;
    }
    return moved;
  }
  CarCoefficient car_coefficient(int j) const {
    return car_tyre_coefficient(j, body_,
                                0.5 * (nominal_.circumference_rl_m + nominal_.circumference_rr_m));
  }
  double tyre_held_value(int j) const { return tyre_held_value_[static_cast<std::size_t>(j)]; }
  // Whether the car fixes coefficient j rather than the log: a stated front drivetrain's rear
  // wheels roll free, so no drive force slips them (docs/tyre-model.md, "A free-rolling axle").
  bool tyre_fixed_by_car(int j) const {
    return j == kDriveSlipCoefficient && tyre_terms_ == TyreTerms::kPhysical &&
           body_.drivetrain == Drivetrain::kFront;
  }
  // Whether a pre-integration rebuilds the GNSS and heading folds or keeps the last ones.
  enum class Folds { kRebuild, kKeep };
  // Every unknown, and the robust loss's weights, to be put back.
  struct Unknowns {
    std::vector<Block3> poses;
    ParamsBlock params;
    Block2 lever;
    double latency, heading_bias, gyro_bias;
    std::vector<Block2> gnss_bias, count_error;
    std::optional<std::vector<float>> gnss_weights;  // none: they stay as they are
  };
  // kKeep leaves out the robust weights (a float per fix): only a fold of the fixes changes them.
  Unknowns unknowns(Folds folds = Folds::kRebuild) const {
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
  void set_unknowns(const Unknowns& u) {
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

  // A solution to come back to: every unknown and the driving states measured at it (20 bytes
  // per wheel sample with a tyre model). The states go with it because each measurement starts
  // from the last: those of a solve that ran away (a tyre model of percents) keep a re-solve
  // there, and measured afresh from the log they lead elsewhere.
  struct Solution {
    Unknowns unknowns;
    std::vector<DrivingState> states;
  };
  Solution solution() const { return {unknowns(), states_}; }
  void return_to(const Solution& solution) {
    set_unknowns(solution.unknowns);
    states_ = solution.states;
  }

  // Every unknown back to where the first solve started (the layer-1 reference's poses, the
  // nominal parameters, the log's own driving state), held coefficients kept where held: after
  // coefficients are held, the rest is solved from where a plain fit starts, not from where a
  // model with more freedom left it (on a skid-steer robot, circumferences of a fraction of a
  // millimetre).
  void restart() {
    poses_ = start_poses_;
    params_ = {nominal_.circumference_rl_m, nominal_.circumference_rr_m, nominal_.track_width_m};
    std::copy(tyre_held_value_.begin(), tyre_held_value_.end(), params_.begin() + kTyreOffset);
    lever_ = {0.0, 0.0};
    latency_ = heading_bias_ = gyro_bias_ = 0.0;
    std::fill(gnss_bias_.begin(), gnss_bias_.end(), Block2{0.0, 0.0});
    std::fill(count_error_.begin(), count_error_.end(), Block2{0.0, 0.0});
    std::fill(gnss_weights_.begin(), gnss_weights_.end(), 1.0f);
    if (!states_.empty()) states_ = driving_states(log_, nominal_);
  }
  bool tyre_held(int j) const { return tyre_held_sigma_[static_cast<std::size_t>(j)] > 0.0; }
  double tyre_held_sigma(int j) const { return tyre_held_sigma_[static_cast<std::size_t>(j)]; }
  int free_tyre_coefficients() const {
    int free = 0;
    for (int j = 0; j < TyreModel::kCoefficients; ++j) free += tyre_in_fit(j) && !tyre_held(j);
    return free;
  }
  TyreModel tyre_model() const {
    return TyreModel::from(Eigen::Map<const TyreModel::Vector>(params_.data() + kTyreOffset));
  }
  const TyreModel::Vector& regressor_rms() const { return regressor_rms_; }
  // The Bayesian information criterion of the last solve: its cost (robust where the loss is)
  // as -log-likelihood, and the unknowns that the model choice adds.
  double information_criterion(const ceres::Solver::Summary& solver) const {
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
        [&](double whitened) { measured_cost += 0.5 * whitened * whitened; });
    const double residuals = static_cast<double>(problem_->NumResiduals()) -
                             static_cast<double>(folded_rows_) +
                             static_cast<double>(measurement_rows_);
    return 2.0 * (solver.final_cost - folded_cost + measured_cost) +
           free_tyre_coefficients() * std::log(residuals);
  }

  // The GNSS noise model from here on: every fix's white sigma scaled by `white_scale`, and a
  // Gauss-Markov error (0: none).
  void set_gnss_noise(double white_scale, double gm_sigma_m, double gm_tau_s) {
    adapted_noise_ = true;
    white_scale_ = white_scale;
    gm_sigma_m_ = gm_sigma_m;
    gm_tau_s_ = gm_tau_s;
    gnss_bias_.assign(gauss_markov() ? keyframes_.size() : 0, Block2{0.0, 0.0});
  }
  // Back to the noise the options state.
  void restore_configured_gnss_noise() {
    set_gnss_noise(1.0, batch_.gnss_gauss_markov_sigma_m, batch_.gnss_gauss_markov_tau_s);
    adapted_noise_ = false;
  }
  bool noise_adapted() const { return adapted_noise_; }
  double gauss_markov_sigma_m() const { return gm_sigma_m_; }
  double gauss_markov_tau_s() const { return gm_tau_s_; }
  // RMS over the fixes of the white part of their sigma.
  double white_gnss_sigma_rms_m() const {
    return rms_over_given_sigmas([this](double given) { return white_gnss_sigma_unshared(given); });
  }

  // RMS of the white sigma the fixes were given (gnss.csv's sigma_m, else the configured one).
  double gnss_sigma_rms_m() const {
    return white_scale_ * rms_over_given_sigmas([](double given) { return given; });
  }

  // Every fix in the problem: measured minus fitted position (metres), robust loss not applied;
  // a modelled Gauss-Markov error counts as part of it.
  // (Computed again at each call, segment by segment: a long log's errors are not held.)
  GnssResidualSource gnss_errors() const {
    return [this](const GnssResidualSink& sink) {
      for_each_fix([&](std::size_t fix, std::size_t segment, const Eigen::Vector2d& whitened) {
        Eigen::Vector2d error = -white_gnss_sigma(fix) * whitened;
        if (gauss_markov())
          error += Eigen::Vector2d(gnss_bias_[segment][0], gnss_bias_[segment][1]);
        sink(log_.gnss.t_s[fix], error);
      });
    };
  }

  // Every odometry interval in the problem: fitted poses, and their relative motion minus the
  // wheels' at the fitted parameters (model_adequacy.hpp). Where the gyro is used, the heading
  // residual is its turn (less the fitted bias) minus the wheels': the poses' own turn is
  // partly the wheels', which would hide what the wheels get wrong.
  std::vector<OdometryResidualSample> odometry_errors() const {
    std::vector<OdometryResidualSample> samples;
    samples.reserve(odometry_blocks_.size());
    for (const OdometryBlock& b : odometry_blocks_) {
      Eigen::Vector3d whitened;
      double cost = 0.0;
      problem_->EvaluateResidualBlock(b.id, false, &cost, whitened.data(), nullptr);
      const std::size_t i = b.segment;
      const Eigen::Matrix3d& sqrt_covariance = odometry_[i].sqrt_covariance;
      OdometryResidualSample sample{
          log_.wheels.t_s[keyframes_[i]],
          log_.wheels.t_s[keyframes_[i + 1]],
          Eigen::Vector3d(poses_[i][0], poses_[i][1], poses_[i][2]),
          Eigen::Vector3d(poses_[i + 1][0], poses_[i + 1][1], poses_[i + 1][2]),
          sqrt_covariance * whitened,
          whitened};
      // The grade the preparation projected with (none: not known, and not tested).
      if (!log_.wheels.grade.empty())
        sample.grade = interval_mean(log_.wheels.grade, keyframes_[i], keyframes_[i + 1]);
      if (i < speed_.size() && speed_[i])
        sample.doppler_error_m = -speed_whitened(i) * speed_[i]->sigma_m;  // Doppler - wheels
      if (i < gyro_turns_.size() && gyro_turns_[i]) {
        const batch::GyroResidual& gyro = *gyro_turns_[i];
        const double wheels_turn = sample.pose1(2) - sample.pose0(2) - sample.error(2);
        const double gyro_turn = gyro.integrated_rad - gyro_bias_ * gyro.duration_s;
        const double odometry_variance = (sqrt_covariance * sqrt_covariance.transpose())(2, 2);
        sample.error(2) = gyro_turn - wheels_turn;
        sample.whitened(2) =
            sample.error(2) / std::sqrt(odometry_variance + gyro.sigma_rad * gyro.sigma_rad);
      }
      samples.push_back(sample);
    }
    return samples;
  }

  // Integrates the odometry of every segment at the current parameters. `slip_floor` loosens the
  // slip noise for a first, coarse solve: started from the layer-1 reference, a nearly rigid
  // odometry chain would take the solver many small steps.
  // `remeasure_states`: false for a round that only re-weights (the driving state stays as the
  // last re-linearisation measured it).
  // Folds::kKeep keeps the folds of GNSS fixes and heading samples of the last pre-integration
  // (they must be at the same unknowns): only the odometry and the Doppler speed, the residuals
  // that the body's numbers reach at the scale of the whole log, are pre-integrated again.
  void preintegrate_all(double slip_floor = 0.0, bool remeasure_states = true,
                        Folds folds = Folds::kRebuild) {
    const bool refold = folds == Folds::kRebuild;
    if (refold) folded_fixes_ = folded_headings_ = 0;
    const OdometryParams at{params_[0], params_[1], params_[2]};
    problem_.reset();  // its blocks point to the folds replaced here; freed before the states
    if (remeasure_states && tyre_fitted() && !tyre_model().plain()) {
      // The driving state from the wheels as the current model counts them: a slipping wheel
      // overstates speed and acceleration by its slip.
      measure_driving_states_again(log_.wheels, log_.imu ? &*log_.imu : nullptr, at, tyre_model(),
                                   body_, states_);
    }
    const TyreConditions tyre{states_, tyre_model(), body_};
    const WheelNoise noise{std::max(noise_.slip_sigma_m_per_sqrt_m, slip_floor),
                           noise_.quantisation_sigma_rev,
                           std::max(noise_.lateral_sigma_m_per_sqrt_m, slip_floor)};
    params_lin_ = Eigen::Map<const batch::ParamsVector>(params_.data());
    odometry_.clear();
    speed_.clear();
    if (refold) {
      folds_.assign(keyframes_.size() - 1, {});
      max_weight_change_ = 0.0f;
      fold_columns_ = fold_columns();
    }
    std::size_t next_fix = 0, next_heading = 0;
    for (std::size_t i = 0; i + 1 < keyframes_.size(); ++i) {
      const PreintegratedSegment segment =
          preintegrate(log_.wheels, keyframes_[i], keyframes_[i + 1], at, noise,
                       tyre_fitted() ? &tyre : nullptr);
      odometry_.push_back(odometry_interval(segment));
      speed_.push_back(std::nullopt);
      if (gap_segment(i)) continue;
      if (use_speed() && rough_segment_[i] == 0) speed_.back() = speed_residual(i, segment, at);
      if (!refold) continue;
      fold_interval(i, segment, next_fix, next_heading);
    }
  }

  // The problem at the current unknowns, built and not solved (as solve() builds it).
  void build() {
    problem_ = std::make_unique<ceres::Problem>();
    folded_rows_ = 0;
    measurement_rows_ = 0;
    add_odometry();
    add_count_priors();
    add_folds();
    if (batch_.use_gyro && log_.imu) add_gyro();
    if (use_speed()) add_speed();
    if (gauss_markov()) add_gauss_markov();
    hold_unrequested();
  }

  // max_iterations: 0 for the configured limit.
  ceres::Solver::Summary solve(int max_iterations = 0) {
    build();
    ceres::Solver::Options solver;
    solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    solver.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
    solver.max_num_iterations = max_iterations > 0 ? max_iterations : batch_.max_solver_iterations;
    solver.num_threads = 1;
    solver.logging_type = ceres::SILENT;
    // Started from the layer-1 reference, the problem is nearly linear: Gauss-Newton steps are
    // good from the start (docs/batch-calibration.md).
    solver.initial_trust_region_radius = 1e8;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, problem_.get(), &summary);
    return summary;
  }

  // Largest relative change of the parameters since the last pre-integration (for the tyre
  // coefficients: of the circumference they make at the log's RMS driving state).
  double relative_change() const { return change_from(params_lin_); }

  // The same measure of the parameters' change since `earlier`.
  double change_from(const Eigen::Ref<const batch::ParamsVector>& earlier) const {
    double change = 0.0;
    for (int p = 0; p < 3; ++p)
      change = std::max(change, std::abs(params_[p] - earlier(p)) / std::abs(earlier(p)));
    for (int j = 0; j < TyreModel::kCoefficients; ++j) {
      const int p = kTyreOffset + j;
      change = std::max(change, std::abs(params_[p] - earlier(p)) * regressor_rms_(j));
    }
    return change;
  }

  // 1-sigma covariance blocks of the global unknowns; none when the information is singular
  // (some unknowns cannot be told apart: batch_covariance.hpp).
  struct Uncertainty {
    Eigen::Matrix<double, batch::kParams, batch::kParams> params =
        Eigen::Matrix<double, batch::kParams, batch::kParams>::Zero();
    Eigen::Matrix2d lever = Eigen::Matrix2d::Zero();
    double gyro_bias{}, heading_bias{}, latency{};
  };
  std::optional<Uncertainty> uncertainty() {
    const auto covariances =
        batch::marginal_covariances(*problem_, {{params_.data(), batch::kParams},
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

  const ParamsBlock& params() const { return params_; }

  // How far the estimate moves with what the log cannot identify and the fit takes as known:
  // per number, one Gauss-Newton step from the solution with it moved by a quarter of its
  // uncertainty, scaled to the whole (the linear sensitivity, without solving again); the outer
  // products summed, as for independent errors. The numbers:
  // - the body's (the physical terms' geometry, docs/tyre-model.md). The GNSS and heading folds
  //   are built once, at the solution: the body reaches them only through the wheels' motion
  //   within one keyframe interval, while it moves the odometry and the Doppler speed over the
  //   whole log;
  // - the tyre coefficients held, by their spread about where they are held (a car's value, and
  //   what the log said while they were free; a regression term, at zero, by what the log said
  //   alone: held_coefficient_sigma). Holding one makes an
  //   error of the car's own value less the held one, which the free ones and the circumferences
  //   take up (the urban drive, seed 8: the brake slip held at zero, c_RL +10 mm at a sigma of
  //   2.5 mm without it). The coefficient
  //   is linear in the pre-integration's Jacobian, which carries the step; the folds keep theirs,
  //   as for the body.
  // The solution and its problem are restored after.
  void add_considered_uncertainty() {
    body_covariance_.setZero();
    held_covariance_.setZero();
    body_responses_.clear();
    held_responses_.clear();
    if (!tyre_terms_) return;
    preintegrate_all(0.0, false);
    const Unknowns solution = unknowns(Folds::kKeep);
    const VehicleBody stated = body_;
    const batch::ParamsVector at = Eigen::Map<const batch::ParamsVector>(params_.data());
    constexpr double kStep = 0.25;
    const auto respond = [&] {
      solve(1);
      const batch::ParamsVector moved =
          (Eigen::Map<const batch::ParamsVector>(params_.data()) - at) / kStep;
      set_unknowns(solution);
      return moved;
    };
    for (int j = 0; j < TyreModel::kCoefficients; ++j) {
      if (!tyre_in_fit(j) || !tyre_held(j)) continue;
      const auto index = static_cast<std::size_t>(j);
      const CarCoefficient car = car_coefficient(j);
      // A regression term has no car's value, and a fit that wandered no word of its own.
      if (!(car.sigma > 0.0) && tyre_held_wandered_[index]) continue;
      const double sigma = held_coefficient_sigma(
          tyre_held_estimate_[index], tyre_held_sigma_[index], car, tyre_held_value_[index]);
      if (!(sigma > 0.0)) continue;
      params_[static_cast<std::size_t>(kTyreOffset) + index] += kStep * sigma;
      const batch::ParamsVector moved = respond();
      held_covariance_ += moved * moved.transpose();
      held_responses_.push_back({j, {stated, kStep * moved, kStep}});
    }
    if (*tyre_terms_ == TyreTerms::kPhysical && !tyre_model().plain()) {
      for (const BodyUncertainty& uncertainty : kBodyUncertainties) {
        body_ = stated;
        body_.*(uncertainty.member) += kStep * uncertainty.sigma(stated);
        preintegrate_all(0.0, false, Folds::kKeep);
        const batch::ParamsVector moved = respond();
        body_covariance_ += moved * moved.transpose();
        body_responses_.push_back({body_, kStep * moved, kStep});
      }
      body_ = stated;
      preintegrate_all(0.0, false, Folds::kKeep);
    }
    solve();  // the solution's own problem again, for the summary (it starts converged)
  }
  const Eigen::Matrix<double, batch::kParams, batch::kParams>& body_covariance() const {
    return body_covariance_;
  }
  // The circumferences' gap to another tyre model's fit of this log, added to their variance:
  // two models that extrapolate to rest differently say how sure either extrapolation is.
  void set_model_spread(const std::array<double, 2>& spread_m) { model_spread_m_ = spread_m; }
  const std::array<double, 2>& model_spread_m() const { return model_spread_m_; }
  // One number moved by `step` of its uncertainty (the body as it then was), and what that moved
  // the parameters by.
  struct Response {
    VehicleBody body;
    batch::ParamsVector moved;
    double step;
  };
  // Per held coefficient (its index in TyreModel::Vector).
  struct HeldResponse {
    int coefficient;
    Response response;
  };
  // Per body number, in kBodyUncertainties' order (none where every coefficient is zero).
  const std::vector<Response>& body_responses() const { return body_responses_; }
  const std::vector<HeldResponse>& held_responses() const { return held_responses_; }
  // Of the parameters, from the held coefficients' spread (add_considered_uncertainty).
  const Eigen::Matrix<double, batch::kParams, batch::kParams>& held_covariance() const {
    return held_covariance_;
  }
  const VehicleBody& body() const { return body_; }
  const Block2& lever() const { return lever_; }
  double gyro_bias() const { return gyro_bias_; }
  double heading_bias() const { return heading_bias_; }
  double latency() const { return latency_; }
  // How far the robust loss's weights moved in the last fold: where they still move, the
  // re-weighting has not settled.
  double max_weight_change() const { return max_weight_change_; }
  std::size_t keyframes() const { return keyframes_.size(); }
  double duration_s() const {
    return log_.wheels.t_s[keyframes_.back()] - log_.wheels.t_s[keyframes_.front()];
  }
  std::size_t gnss_residuals() const { return gnss_residuals_; }
  // The Doppler residuals' noise from the next pre-integration on: the configured one times this.
  void set_speed_noise(double scale) { speed_scale_ = scale; }
  double speed_noise_scale() const { return speed_scale_; }
  // Every Doppler residual at the current unknowns, whitened (robust loss not applied).
  std::vector<double> speed_whitened() const {
    std::vector<double> whitened;
    for (std::size_t i = 0; i < speed_.size(); ++i)
      if (speed_[i]) whitened.push_back(speed_whitened(i));
    return whitened;
  }
  // Keyframe interval i's Doppler residual (it must have one), whitened: (wheels - Doppler) /
  // sigma.
  double speed_whitened(std::size_t i) const {
    double r = 0.0;
    (*speed_[i])(params_.data(), lever_.data(), &latency_, count_error_[i].data(),
                 count_error_[i + 1].data(), &r);
    return r;
  }
  // Keyframe intervals whose Doppler speed is in the fit.
  std::size_t speed_intervals() const {
    return static_cast<std::size_t>(
        std::count_if(speed_.begin(), speed_.end(), [](const auto& r) { return r.has_value(); }));
  }

 private:
  bool use_speed() const { return doppler_sigma_mps_ > 0.0; }

  // Segment i's Doppler speed against its wheels (none where the fixes do not cover it or a wheel
  // turns backwards: the Doppler speed has no sign).
  std::optional<batch::SpeedResidual> speed_residual(std::size_t i, const PreintegratedSegment& seg,
                                                     const OdometryParams& at) const {
    // Below this the speed's magnitude is biased by its own noise (and reversing would hide).
    constexpr double kMinSpeedMps = 1.0;
    const double begin = log_.wheels.t_s[keyframes_[i]], end = log_.wheels.t_s[keyframes_[i + 1]];
    const auto interval = batch::doppler_interval(log_.gnss, begin, end, speed_max_gap_s_,
                                                  std::max(kMinSpeedMps, 5.0 * doppler_sigma_mps_));
    if (!interval) return std::nullopt;
    batch::SpeedResidual r;
    for (std::size_t k = keyframes_[i] + 1; k <= keyframes_[i + 1]; ++k) {
      const WheelIncrement n = log_.wheels.increment(k);
      if (n.rev_rl < 0.0 || n.rev_rr < 0.0) return std::nullopt;
      r.half_revolutions[0] += 0.5 * n.rev_rl;
      r.half_revolutions[1] += 0.5 * n.rev_rr;
      if (!tyre_fitted()) continue;
      r.half_tyre_revolutions.row(0) +=
          0.5 * n.rev_rl * tyre_regressors(states_[k], RearWheel::kLeft, body_).transpose();
      r.half_tyre_revolutions.row(1) +=
          0.5 * n.rev_rr * tyre_regressors(states_[k], RearWheel::kRight, body_).transpose();
      const double half_square = 0.5 * square(side_slip_regressor(states_[k]));
      r.half_side_slip_revolutions[0] += 0.5 * n.rev_rl * half_square;
      r.half_side_slip_revolutions[1] += 0.5 * n.rev_rr * half_square;
    }
    const double duration = end - begin;
    const double doppler_variance =
        square(doppler_sigma_mps_) *
        std::max(interval->sum_squared_weights_s2, batch_.gnss_speed_correlation_s * duration);
    // The slip noise of the two arcs, each half the distance.
    const double slip_variance = 0.25 * square(noise_.slip_sigma_m_per_sqrt_m) *
                                 (at.circumference_rl_m * 2.0 * r.half_revolutions[0] +
                                  at.circumference_rr_m * 2.0 * r.half_revolutions[1]);
    r.sigma_m = speed_scale_ * std::sqrt(doppler_variance + slip_variance);
    r.speed_change_mps = interval->speed_change_mps;
    if (!batch_.estimate_lever_arm) {
      // Held at zero: the integral alone.
      double distance = 0.0;
      for (std::size_t f = 0; f < interval->fixes.size(); ++f)
        distance += interval->weights_s[f] * log_.gnss.speed_mps[interval->fixes[f]];
      r.shares.push_back({1.0, distance, 0.0});
      return r;
    }
    const auto& t = log_.wheels.t_s;
    for (std::size_t f = 0; f < interval->fixes.size(); ++f) {
      const std::size_t j = interval->fixes[f];
      const std::size_t s = segment_sample(seg, std::clamp(log_.gnss.t_s[j], begin, end));
      const double yaw_rate = (seg.delta[s + 1].z() - seg.delta[s].z()) /
                              (t[seg.first_sample + s + 1] - t[seg.first_sample + s]);
      r.shares.push_back({interval->weights_s[f], log_.gnss.speed_mps[j], yaw_rate});
    }
    return r;
  }

  void add_speed() {
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

  // The pre-integrated motion of segment i from its keyframe to time t_s (inside the segment),
  // with the reference point's velocity there (keyframe frame).
  struct MotionAt {
    batch::RelativeMotion motion;
    Eigen::Vector2d velocity;
  };
  // The segment's sample s whose increment to s + 1 spans t_s (inside the segment).
  std::size_t segment_sample(const PreintegratedSegment& seg, double t_s) const {
    const auto& t = log_.wheels.t_s;
    const auto first = t.begin() + static_cast<long>(seg.first_sample);
    const auto last = t.begin() + static_cast<long>(seg.last_sample);
    return static_cast<std::size_t>(std::upper_bound(first, last, t_s) - first) - 1;
  }

  MotionAt motion_at(std::size_t i, const PreintegratedSegment& seg, double t_s) const {
    const auto& t = log_.wheels.t_s;
    const std::size_t s = segment_sample(seg, t_s);
    const std::size_t k = seg.first_sample + s;
    const double dt = t[k + 1] - t[k];
    const double w = (t_s - t[k]) / dt;
    MotionAt at;
    at.motion.delta = (1.0 - w) * seg.delta[s] + w * seg.delta[s + 1];
    at.motion.J_delta_params =
        (1.0 - w) * params_jacobian(seg, s) + w * params_jacobian(seg, s + 1);
    at.motion.J_delta_first_increment =
        (1.0 - w) * seg.J_delta_first_increment[s] + w * seg.J_delta_first_increment[s + 1];
    at.motion.params_lin = params_lin_;
    if (rough_segment_[i] != 0) at.motion.J_delta_params.setZero();
    at.velocity = (seg.delta[s + 1].head<2>() - seg.delta[s].head<2>()) / dt;
    return at;
  }

  // Calls visit(k, motion) for every sample k of a stream's times `t_s` (GNSS fixes, heading
  // samples) inside segment i, from `next` on (samples before the segment are skipped; `next`
  // ends past it).
  template <typename Visit>
  void visit_fixes(std::size_t i, const PreintegratedSegment& seg, const std::vector<double>& t_s,
                   std::size_t& next, Visit&& visit) const {
    const double begin = log_.wheels.t_s[keyframes_[i]], end = log_.wheels.t_s[keyframes_[i + 1]];
    while (next < t_s.size() && t_s[next] < begin) ++next;
    for (; next < t_s.size() && t_s[next] < end; ++next) visit(next, motion_at(i, seg, t_s[next]));
  }

  // Fix j's whitened residual at the current unknowns (robust loss not applied).
  Eigen::Vector2d whitened_fix(std::size_t j, std::size_t i, const MotionAt& at) const {
    const batch::GnssResidual residual{at.motion, at.velocity,
                                       Eigen::Vector2d(log_.gnss.x_m[j], log_.gnss.y_m[j]),
                                       white_gnss_sigma(j)};
    const double* bias = gauss_markov() ? gnss_bias_[i].data() : zero_bias_.data();
    Eigen::Vector2d whitened;
    residual(poses_[i].data(), params_.data(), lever_.data(), &latency_, bias,
             count_error_[i].data(), whitened.data());
    return whitened;
  }

  // rho(s), rho'(s) of the GNSS loss at a squared whitened residual s.
  std::array<double, 3> robust(double s) const {
    std::array<double, 3> rho{s, 1.0, 0.0};
    if (loss_) loss_->Evaluate(s, rho.data());
    return rho;
  }

  bool use_heading() const { return batch_.use_heading && log_.heading; }

  // The fixes of segment i, each weighted by the robust loss at the current unknowns, and its
  // heading samples folded into one residual.
  void fold_interval(std::size_t i, const PreintegratedSegment& seg, std::size_t& next_fix,
                     std::size_t& next_heading) {
    batch::RowFold<batch::kFoldedColumns> fold;
    const Eigen::Vector2d origin(poses_[i][0], poses_[i][1]);
    visit_fixes(i, seg, log_.gnss.t_s, next_fix, [&](std::size_t j, const MotionAt& at) {
      const float weight = static_cast<float>(robust(whitened_fix(j, i, at).squaredNorm())[1]);
      max_weight_change_ = std::max(max_weight_change_, std::abs(weight - gnss_weights_[j]));
      gnss_weights_[j] = weight;
      ++folded_fixes_;
      batch::FoldedIntervalResidual::add_fix(
          fold, at.motion, at.velocity,
          Eigen::Vector2d(log_.gnss.x_m[j], log_.gnss.y_m[j]) - origin, white_gnss_sigma(j),
          weight);
    });
    if (use_heading()) {
      const HeadingStream& heading = *log_.heading;
      visit_fixes(i, seg, heading.t_s, next_heading, [&](std::size_t j, const MotionAt& at) {
        const double predicted = poses_[i][2] + at.motion.delta(2) + heading_bias_;
        const double measured = predicted + batch::wrapped(heading.heading_rad[j] - predicted);
        ++folded_headings_;
        batch::FoldedIntervalResidual::add_heading(fold, at.motion, measured,
                                                   sensors_.heading_sigma_rad);
      });
    }
    if (!fold.empty()) folds_[i] = {origin, fold.factor(fold_columns_), &params_lin_};
  }

  // Calls visit_fix(fix, segment, whitened residual) for every fix in the problem and
  // visit_heading(whitened residual) for every heading sample, at the current unknowns and as the
  // folds linearise them, pre-integrating again segment by segment (memory stays per segment).
  template <typename VisitFix, typename VisitHeading>
  void for_each_measurement(VisitFix&& visit_fix, VisitHeading&& visit_heading) const {
    const OdometryParams at{params_lin_(0), params_lin_(1), params_lin_(2)};
    const TyreConditions tyre{states_,
                              TyreModel::from(params_lin_.tail<TyreModel::kCoefficients>()), body_};
    constexpr bool kHeadings = !std::is_same_v<std::decay_t<VisitHeading>, std::nullptr_t>;
    std::size_t next_fix = 0, next_heading = 0;
    for (std::size_t i = 0; i + 1 < keyframes_.size(); ++i) {
      if (gap_segment(i)) continue;
      const PreintegratedSegment seg = preintegrate(log_.wheels, keyframes_[i], keyframes_[i + 1],
                                                    at, noise_, tyre_fitted() ? &tyre : nullptr);
      visit_fixes(i, seg, log_.gnss.t_s, next_fix, [&](std::size_t j, const MotionAt& motion) {
        visit_fix(j, i, whitened_fix(j, i, motion));
      });
      if constexpr (kHeadings) {
        if (!use_heading()) continue;
        visit_fixes(i, seg, log_.heading->t_s, next_heading,
                    [&](std::size_t j, const MotionAt& motion) {
                      const batch::HeadingResidual residual{
                          motion.motion, log_.heading->heading_rad[j], sensors_.heading_sigma_rad};
                      double whitened = 0.0;
                      residual(poses_[i].data(), params_.data(), &heading_bias_,
                               count_error_[i].data(), &whitened);
                      visit_heading(whitened);
                    });
      }
    }
  }
  template <typename Visit>
  void for_each_fix(Visit&& visit) const {
    for_each_measurement(std::forward<Visit>(visit), nullptr);
  }

  // A segment that is a wheel gap: no odometry links its keyframes (GNSS and the gyro do).
  bool gap_segment(std::size_t i) const { return log_.wheels.breaks_at(keyframes_[i + 1]); }

  // Whether parameter p is estimated in this solve (the rest are held where they are).
  bool param_free(int p) const {
    if (p < 2) return true;
    if (p == 2) return batch_.estimate_track_width;
    return tyre_in_fit(p - kTyreOffset) && !tyre_held(p - kTyreOffset);
  }

  // The entries of a fold's phi (batch_folded_residuals.hpp) that this solve can move.
  batch::ColumnSelection<batch::kFoldedColumns> fold_columns() const {
    batch::ColumnSelection<batch::kFoldedColumns> selection;
    selection.constant_column = batch::kFoldedConstantColumn;
    for (int c = 0; c < batch::kFoldedParamsColumn; ++c)
      selection.kept.push_back(static_cast<std::uint8_t>(c));
    for (int p = 0; p < batch::kParams; ++p) {
      if (param_free(p))
        selection.kept.push_back(static_cast<std::uint8_t>(batch::kFoldedParamsColumn + p));
    }
    const auto keep_or_hold = [&](int column, bool free, double value) {
      if (free) {
        selection.kept.push_back(static_cast<std::uint8_t>(column));
      } else {
        selection.held_values(column) = value;
      }
    };
    for (int w = 0; w < 2; ++w)
      keep_or_hold(batch::kFoldedCountColumn + w, quantisation_sigma_rev_ > 0.0, 0.0);
    for (int a = 0; a < 2; ++a) {
      keep_or_hold(batch::kFoldedLeverColumn + a, batch_.estimate_lever_arm,
                   lever_[static_cast<std::size_t>(a)]);
    }
    keep_or_hold(batch::kFoldedLatencyColumn, batch_.estimate_latency, latency_);
    // Without heading samples the column is zero in every row.
    keep_or_hold(batch::kFoldedHeadingColumn, use_heading(), 0.0);
    return selection;
  }

  bool gentle_limits() const {
    return batch_.gentle_max_speed_mps > 0.0 || batch_.gentle_max_longitudinal_mps2 > 0.0 ||
           batch_.gentle_max_lateral_mps2 > 0.0;
  }
  // An interval whose driving exceeds a gentle limit: no odometry residual, and the fixes inside
  // it use the wheels only to interpolate from the keyframe (no parameter derivative).
  void mark_gentle_segments() {
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

 public:
  // Keyframe intervals with odometry in the fit (not a gap, inside the gentle limits), of all.
  std::pair<std::size_t, std::size_t> gentle_intervals() const {
    std::size_t used = 0;
    for (std::size_t i = 0; i + 1 < keyframes_.size(); ++i)
      used += (!gap_segment(i) && rough_segment_[i] == 0) ? 1 : 0;
    return {used, keyframes_.size() - 1};
  }

 private:
  // Per keyframe interval, the odometry residual of its pre-integration (the per-sample motion
  // lives only while its fixes are folded). The problem's blocks point to these rather than own
  // copies, so that a long log keeps one: they are replaced only after the problem is freed.
  struct OdometryInterval {
    batch::OdometryResidual residual;
    Eigen::Matrix3d sqrt_covariance;  // lower Cholesky factor: error = it x whitened
  };
  OdometryInterval odometry_interval(const PreintegratedSegment& segment) const {
    const std::size_t last = segment.delta.size() - 1;
    // A tiny floor keeps a standing-still segment's information finite.
    const Eigen::Matrix3d covariance =
        segment.covariance + Eigen::Vector3d(1e-10, 1e-10, 1e-12).asDiagonal().toDenseMatrix();
    const Eigen::Matrix3d L = covariance.llt().matrixL();
    return {{{segment.delta[last], params_jacobian(segment, last),
              segment.J_delta_first_increment[last], params_lin_},
             segment.J_end_last_increment,
             L.triangularView<Eigen::Lower>().solve(Eigen::Matrix3d::Identity())},
            L};
  }

  void add_odometry() {
    odometry_blocks_.clear();
    for (std::size_t i = 0; i < odometry_.size(); ++i) {
      if (gap_segment(i) || rough_segment_[i] != 0) continue;
      odometry_blocks_.push_back(
          {problem_->AddResidualBlock(new ceres::AutoDiffCostFunction<batch::OdometryResidual, 3, 3,
                                                                      3, batch::kParams, 2, 2>(
                                          &odometry_[i].residual, ceres::DO_NOT_TAKE_OWNERSHIP),
                                      nullptr, poses_[i].data(), poses_[i + 1].data(),
                                      params_.data(), count_error_[i].data(),
                                      count_error_[i + 1].data()),
           i});
    }
  }

  // Without a quantisation (exact wheel angles or speeds) the count errors stay zero.
  void add_count_priors() {
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

  // The sigma of fix j's residual. A configured Gauss-Markov error is taken out of the
  // configured total; an adapted model's white part was estimated as such. The Gauss-Markov
  // error is held per keyframe, but it drifts within one (by sigma^2 2 dt / (3 tau) on average
  // over the keyframe, for dt << tau), and that drift is shared by the keyframe's n fixes: each
  // fix carries n times its variance, so that the keyframe as a whole is weighted right.
  double white_gnss_sigma(std::size_t j) const {
    const double given = log_.gnss.sigma_m.empty() ? sensors_.gnss_sigma_m : log_.gnss.sigma_m[j];
    if (!gauss_markov()) return white_scale_ * given;
    const double gm2 = gm_sigma_m_ * gm_sigma_m_;
    const double drift = std::min(2.0 * batch_.keyframe_interval_s / (3.0 * gm_tau_s_), 1.0);
    return std::sqrt(square(white_gnss_sigma_unshared(given)) +
                     gnss_fixes_per_keyframe_ * gm2 * drift);
  }
  // The white part of a fix given `given`, without the keyframe's share of the drift.
  double white_gnss_sigma_unshared(double given) const {
    if (!gauss_markov() || adapted_noise_) return white_scale_ * given;
    return std::sqrt(std::max(given * given - gm_sigma_m_ * gm_sigma_m_, 0.01 * given * given));
  }
  static double square(double v) { return v * v; }
  // RMS over the fixes of sigma(the sigma each was given: gnss.csv's, else the configured one).
  template <typename Sigma>
  double rms_over_given_sigmas(const Sigma& sigma) const {
    if (log_.gnss.sigma_m.empty()) return sigma(sensors_.gnss_sigma_m);
    double sum = 0.0;
    for (const double given : log_.gnss.sigma_m) sum += square(sigma(given));
    return std::sqrt(sum / static_cast<double>(log_.gnss.sigma_m.size()));
  }

  ceres::LossFunction* gnss_loss() const {
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

  void add_folds() {
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

  // Zero-order hold of the yaw rate over each keyframe interval the IMU covers.
  void add_gyro() {
    gyro_turns_.assign(keyframes_.size(), std::nullopt);
    const ImuStream& imu = *log_.imu;
    const double step_s = median_step_s(imu.t_s);
    if (imu.size() < 2 || step_s <= 0.0) return;
    std::size_t j = 0;
    for (std::size_t i = 0; i + 1 < keyframes_.size(); ++i) {
      const double begin = log_.wheels.t_s[keyframes_[i]], end = log_.wheels.t_s[keyframes_[i + 1]];
      if (imu.t_s.front() > begin || imu.t_s.back() < end) continue;
      while (j + 1 < imu.size() && imu.t_s[j + 1] <= begin) ++j;
      double integrated = 0.0, largest_gap = 0.0;
      for (std::size_t m = j; m + 1 < imu.size() && imu.t_s[m] < end; ++m) {
        const double overlap = std::min(imu.t_s[m + 1], end) - std::max(imu.t_s[m], begin);
        integrated += imu.wz_radps[m] * overlap;
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

  void add_gauss_markov() {
    const double sigma = gm_sigma_m_;
    problem_->AddResidualBlock(new ceres::AutoDiffCostFunction<batch::GaussMarkovPrior, 2, 2>(
                                   new batch::GaussMarkovPrior{sigma}),
                               nullptr, gnss_bias_[0].data());
    for (std::size_t i = 0; i + 1 < keyframes_.size(); ++i) {
      const double dt = log_.wheels.t_s[keyframes_[i + 1]] - log_.wheels.t_s[keyframes_[i]];
      const double phi = std::exp(-dt / gm_tau_s_);
      problem_->AddResidualBlock(
          new ceres::AutoDiffCostFunction<batch::GaussMarkovResidual, 2, 2, 2>(
              new batch::GaussMarkovResidual{phi, sigma * std::sqrt(1.0 - phi * phi)}),
          nullptr, gnss_bias_[i].data(), gnss_bias_[i + 1].data());
    }
  }

  void hold_unrequested() {
    const auto hold = [&](double* block, bool estimate) {
      if (!estimate && problem_->HasParameterBlock(block))
        problem_->SetParameterBlockConstant(block);
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

  const Log& log_;
  const ReferenceOptions& sensors_;  // the sensors' noise
  const BatchOptions& batch_;
  VehicleBody body_;  // what the tyre model's physical terms are computed with
  std::vector<std::size_t> keyframes_;
  // Per keyframe interval (odometry_interval); the problem's blocks point to these.
  std::vector<OdometryInterval> odometry_;
  // Per keyframe interval: its Doppler speed residual, where the log has one that covers it.
  std::vector<std::optional<batch::SpeedResidual>> speed_;
  double speed_max_gap_s_ = 1.0;    // two Doppler fixes further apart leave the interval out
  double doppler_sigma_mps_ = 0.0;  // 0: no Doppler residuals
  double speed_scale_ = 1.0;        // of the Doppler residuals' sigma (set_speed_noise)
  // Per keyframe interval; an empty factor: nothing measured there.
  std::vector<batch::FoldedIntervalResidual> folds_;
  batch::ColumnSelection<batch::kFoldedColumns> fold_columns_;  // of the folds being built
  std::size_t folded_fixes_ = 0, folded_headings_ = 0;
  std::vector<float> gnss_weights_;  // per fix: the robust loss's weight in the last fold
  float max_weight_change_ = 0.0f;   // ... and its largest change there
  std::unique_ptr<ceres::LossFunction> loss_;
  std::size_t folded_rows_ = 0;       // rows of the folded blocks in the problem
  std::size_t measurement_rows_ = 0;  // ... and the measurement rows they stand for
  WheelNoise noise_;
  double quantisation_sigma_rev_ = 0.0;
  batch::ParamsVector params_lin_ = batch::ParamsVector::Zero();
  std::vector<DrivingState> states_;  // per wheel sample; empty without tyre model and limits
  std::vector<std::uint8_t> rough_segment_;  // per interval: outside the gentle limits
  TyreModel::Vector regressor_rms_ = TyreModel::Vector::Zero();
  std::optional<TyreTerms> tyre_terms_;  // the family of tyre coefficients fitted (none: plain)
  // Of the parameters, from the body's uncertainty and the held coefficients' spread
  // (add_considered_uncertainty).
  Eigen::Matrix<double, batch::kParams, batch::kParams> body_covariance_ =
      Eigen::Matrix<double, batch::kParams, batch::kParams>::Zero();
  Eigen::Matrix<double, batch::kParams, batch::kParams> held_covariance_ =
      Eigen::Matrix<double, batch::kParams, batch::kParams>::Zero();
  std::vector<Response> body_responses_;
  std::vector<HeldResponse> held_responses_;
  std::array<double, 2> model_spread_m_{};
  std::array<double, TyreModel::kCoefficients> tyre_held_sigma_{};     // > 0: held
  std::array<double, TyreModel::kCoefficients> tyre_held_estimate_{};  // its value while free
  std::array<double, TyreModel::kCoefficients> tyre_held_value_{};     // where it is held
  std::array<bool, TyreModel::kCoefficients> tyre_held_wandered_{};    // its free fit wandered
  std::unique_ptr<ceres::Problem> problem_;
  std::size_t gnss_residuals_ = 0;
  std::vector<ceres::ResidualBlockId> fold_blocks_;
  struct OdometryBlock {
    ceres::ResidualBlockId id;
    std::size_t segment;
  };
  std::vector<OdometryBlock> odometry_blocks_;
  std::vector<std::optional<batch::GyroResidual>> gyro_turns_;  // per interval, where used
  // The GNSS noise model (configured, or adapted by set_gnss_noise).
  bool adapted_noise_ = false;
  double white_scale_ = 1.0;
  double gnss_fixes_per_keyframe_ = 1.0;
  double gm_sigma_m_ = 0.0;
  double gm_tau_s_ = 60.0;
  // Unknowns.
  std::vector<Block3> poses_;
  std::vector<Block3> start_poses_;
  ParamsBlock params_{};
  Block2 lever_{0.0, 0.0};
  OdometryParams nominal_;
  double latency_ = 0.0;
  double heading_bias_ = 0.0;
  double gyro_bias_ = 0.0;
  std::vector<Block2> gnss_bias_;
  std::vector<Block2> count_error_;
  Block2 zero_bias_{0.0, 0.0};  // stands in for the GNSS bias when it is not modelled
};

// Each rear wheel's effective circumference rolling straight at a steady `speed`: c_i times the
// tyre model's factor there, its sigma from the data's covariance (`covariance`, the parameters')
// and from the body's responses, each the parameters' move and the factor's own change with the
// body number (the rolling resistance's slip at constant speed is in the factor, so a body number
// moves both c_i and the factor).
ReferenceCircumference reference_circumference(
    const BatchProblem& batch, const ParamsBlock& p,
    const Eigen::Matrix<double, batch::kParams, batch::kParams>& covariance, double speed,
    double max_sigma) {
  DrivingState steady;
  steady.speed_mps = static_cast<float>(speed);
  const batch::ParamsVector at = Eigen::Map<const batch::ParamsVector>(p.data());
  const auto rolling = [&](const batch::ParamsVector& params, const VehicleBody& body, int wheel) {
    const TyreModel model = TyreModel::from(params.tail<TyreModel::kCoefficients>());
    return params(wheel) *
           tyre_factor(model, steady, wheel == 0 ? RearWheel::kLeft : RearWheel::kRight, body);
  };
  ReferenceCircumference r;
  r.speed_mps = speed;
  r.identified = true;
  for (int wheel = 0; wheel < 2; ++wheel) {
    const double value = rolling(at, batch.body(), wheel);
    batch::ParamsVector gradient = batch::ParamsVector::Zero();
    for (int j = 0; j < batch::kParams; ++j) {
      batch::ParamsVector moved = at;
      const double step = 1e-7 * std::max(1.0, std::abs(at(j)));
      moved(j) += step;
      gradient(j) = (rolling(moved, batch.body(), wheel) - value) / step;
    }
    double variance = gradient.dot(covariance * gradient);
    const auto add_response = [&](const BatchProblem::Response& response) {
      const double change =
          (rolling(at + response.moved, response.body, wheel) - value) / response.step;
      variance += change * change;
    };
    for (const BatchProblem::Response& response : batch.body_responses()) add_response(response);
    for (const BatchProblem::HeldResponse& held : batch.held_responses())
      add_response(held.response);
    const double sigma = std::sqrt(std::max(variance, 0.0));
    (wheel == 0 ? r.circumference_rl_m : r.circumference_rr_m) = value;
    (wheel == 0 ? r.sigma_rl_m : r.sigma_rr_m) = sigma;
    r.identified = r.identified && std::isfinite(sigma) && sigma <= max_sigma;
  }
  return r;
}

// A plain model that does not explain the log: the verdict says what would (the batch's own and
// the one judged for another method read alike).
void suggest_tyre_model(ModelAdequacy& adequacy) {
  if (!adequacy.judged || adequacy.explains) return;
  adequacy.verdict +=
      "; the batch method's tyre_model: physical (or auto) fits a circumference that follows the "
      "driving state (docs/tyre-model.md)";
}

// Why a circumference beside a tyre model is not identified: at rest it is an extrapolation from
// the states driven, and its sigma carries the log's own noise, what the log cannot identify (the
// body's numbers, the held coefficients) and the two models' gap. Every share is named, largest
// first, with what would shrink it, so that the user states or drives what matters most.
std::string extrapolation_verdict(const BatchSummary& summary, std::size_t wheel, double sigma_m,
                                  double spread_m, bool has_doppler) {
  struct Share {
    double size_m;
    std::string text, advice;
  };
  std::vector<Share> shares;
  // A share with parts: its total, and the part that moves the circumference most, which `act`
  // on names.
  const auto add_parts = [&](double total_m, const auto& parts, const char* from, auto act) {
    const auto largest = std::max_element(
        parts.begin(), parts.end(),
        [wheel](const auto& a, const auto& b) { return a.sigma_m[wheel] < b.sigma_m[wheel]; });
    if (!(total_m > 0.0) || largest == parts.end()) return;
    shares.push_back({total_m,
                      fmt::format("{:.2g} mm {}, {:.2g} mm of it from {}", 1e3 * total_m, from,
                                  1e3 * largest->sigma_m[wheel], largest->key),
                      act(largest->key)});
  };
  add_parts(summary.body_sigma_m[wheel], summary.body_sigma_parts, "from the body's uncertainty",
            [](const std::string&) { return std::string("state vehicle.yaml's body"); });
  add_parts(summary.held_sigma_m[wheel], summary.held_sigma_parts,
            "from the tyre coefficients held",
            [](const std::string& key) { return "drive more of what shows " + key; });
  if (spread_m > 0.0) {
    shares.push_back({spread_m,
                      fmt::format("{:.2g} mm from the gap to where the physical terms' fit puts it",
                                  1e3 * spread_m),
                      "drive more gently"});
  }
  double named_variance = 0.0;
  for (const Share& share : shares) named_variance += share.size_m * share.size_m;
  if (std::isfinite(sigma_m)) {
    const double own_m = std::sqrt(std::max(0.0, sigma_m * sigma_m - named_variance));
    const double misfit = summary.misfit_sigma_scale;
    shares.push_back(
        {own_m,
         misfit > 1.0 ? fmt::format("{:.2g} mm from the log's own noise, widened {:.2g} times by "
                                    "the model's misfit (chi2/dof {:.3g})",
                                    1e3 * own_m, misfit, summary.model_adequacy.chi2_per_dof)
                      : fmt::format("{:.2g} mm from the log's own noise", 1e3 * own_m),
         has_doppler ? "drive longer and more gently"
                     : "drive longer and more gently, or log the GNSS receiver's Doppler speed "
                       "(gnss.csv speed_mps)"});
  }
  std::stable_sort(shares.begin(), shares.end(),
                   [](const Share& a, const Share& b) { return a.size_m > b.size_m; });
  std::vector<std::string> texts, advice;
  for (const Share& share : shares) {
    texts.push_back(share.text);
    if (std::find(advice.begin(), advice.end(), share.advice) == advice.end())
      advice.push_back(share.advice);
  }
  const std::string extrapolation =
      "with the tyre model the circumference at rest is an extrapolation from this drive's slip "
      "and load";
  if (texts.empty()) return extrapolation + " (drive longer and more gently)";
  return fmt::format("{} (of its 1-sigma, {}: {})", extrapolation, fmt::join(texts, "; "),
                     fmt::join(advice, "; "));
}

// A plain circumference whose sigma carries its gap to a tyre model's fit (tyre_model none chosen
// by hand, judged: tyre_model_selection.cpp).
std::string plain_gap_verdict(double sigma_m, double gap_m) {
  return fmt::format(
      "the plain model's circumference is the one this drive rolled on, slip and load in it: a "
      "tyre model, which fits this log better, puts the circumference at rest {:.3g} mm away (of "
      "its 1-sigma, {:.2g} mm from the log's own noise); use tyre_model: auto",
      1e3 * gap_m, 1e3 * std::sqrt(std::max(0.0, sigma_m * sigma_m - gap_m * gap_m)));
}

// A circumference that only the misfit's widening leaves unidentified.
std::string misfit_verdict(const BatchSummary& summary) {
  return fmt::format(
      "the model does not fit this log: its odometry residuals are {:.2g} times as wide as their "
      "noise (chi2/dof {:.3g}), and so is every sigma (the model line says what they follow; "
      "drive more gently, or choose a tyre_model that explains the log)",
      summary.misfit_sigma_scale, summary.model_adequacy.chi2_per_dof);
}

// Fills the summary from the solved problem: every parameter with its sigma and verdict, and
// the termination (a circumference that is not identified makes the result unusable).
void summarise(const Log& log, const BatchOptions& b, BatchProblem& batch,
               const ceres::Solver::Summary& solver, BatchSummary& summary) {
  const auto& p = batch.params();
  summary.estimate = {p[0], p[1], p[2]};
  // An adapted noise that ran away and whose widening could not be measured leaves no sigma.
  const auto uncertainty =
      std::isfinite(summary.gnss_noise.covariance_scale) ? batch.uncertainty() : std::nullopt;
  const double inf = std::numeric_limits<double>::infinity();
  const auto sigma = [&](double variance) { return uncertainty ? std::sqrt(variance) : inf; };
  BatchProblem::Uncertainty u = uncertainty.value_or(BatchProblem::Uncertainty{});
  summary.model_adequacy = assess_model_adequacy(batch.odometry_errors(),
                                                 batch.tyre_fitted() && !batch.tyre_model().plain()
                                                     ? tyre_model_option(*batch.tyre_terms())
                                                     : "");
  summary.misfit_sigma_scale = misfit_sigma_scale(summary.model_adequacy);
  const double scale =
      summary.gnss_noise.covariance_scale * summary.misfit_sigma_scale * summary.misfit_sigma_scale;
  u.params *= scale;
  u.lever *= scale;
  u.gyro_bias *= scale;
  u.heading_bias *= scale;
  u.latency *= scale;
  // The data's own covariance, before the body's and the models' spread: a circumference rolling
  // at a reference speed adds the body's share per body number itself, and makes no
  // extrapolation to rest.
  const Eigen::Matrix<double, batch::kParams, batch::kParams> data_covariance = u.params;
  u.params += batch.body_covariance() + batch.held_covariance();
  const std::array<double, 2>& spread = batch.model_spread_m();
  for (int w = 0; w < 2; ++w)
    u.params(w, w) += spread[static_cast<std::size_t>(w)] * spread[static_cast<std::size_t>(w)];
  summary.model_spread_m = spread;
  summary.body_sigma_m = {std::sqrt(batch.body_covariance()(0, 0)),
                          std::sqrt(batch.body_covariance()(1, 1))};
  const auto moved_circumferences = [](const BatchProblem::Response& response) {
    return std::array<double, 2>{std::abs(response.moved(0)) / response.step,
                                 std::abs(response.moved(1)) / response.step};
  };
  summary.body_sigma_parts.clear();
  for (std::size_t i = 0; i < batch.body_responses().size(); ++i) {
    summary.body_sigma_parts.push_back(
        {kBodyUncertainties[i].key, moved_circumferences(batch.body_responses()[i])});
  }
  summary.held_sigma_m = {std::sqrt(batch.held_covariance()(0, 0)),
                          std::sqrt(batch.held_covariance()(1, 1))};
  summary.held_sigma_parts.clear();
  for (const BatchProblem::HeldResponse& held : batch.held_responses()) {
    const auto j = static_cast<std::size_t>(held.coefficient);
    summary.held_sigma_parts.push_back(
        {tyre_parameter_name(kTyreCoefficients[j]), moved_circumferences(held.response),
         held.response.moved(kTyreOffset + held.coefficient) / held.response.step});
  }
  summary.parameters = {
      {"circumference_rl_m", p[0], sigma(u.params(0, 0)), true, true, ""},
      {"circumference_rr_m", p[1], sigma(u.params(1, 1)), true, true, ""},
      {"track_width_m", p[2], sigma(u.params(2, 2)), b.estimate_track_width, true, ""},
      {"gyro_bias_radps", batch.gyro_bias(), sigma(u.gyro_bias), b.estimate_gyro_bias, true, ""},
      {"heading_bias_rad", batch.heading_bias(), sigma(u.heading_bias), b.estimate_heading_bias,
       true, ""},
      {"lever_arm_x_m", batch.lever()[0], sigma(u.lever(0, 0)), b.estimate_lever_arm, true, ""},
      {"lever_arm_y_m", batch.lever()[1], sigma(u.lever(1, 1)), b.estimate_lever_arm, true, ""},
      {"latency_s", batch.latency(), sigma(u.latency), b.estimate_latency, true, ""}};
  std::vector<double> thresholds{b.max_sigma_circumference_m,  b.max_sigma_circumference_m,
                                 b.max_sigma_track_width_m,    b.max_sigma_gyro_bias_radps,
                                 b.max_sigma_heading_bias_rad, b.max_sigma_lever_arm_m,
                                 b.max_sigma_lever_arm_m,      b.max_sigma_latency_s};
  const LogCoverage coverage = log_coverage(log, summary.coverage);
  std::vector<bool> block_used{
      true, true, true, log.imu.has_value() && b.use_gyro, log.heading.has_value() && b.use_heading,
      true, true, true};
  for (int j = 0; j < TyreModel::kCoefficients; ++j) {
    const int p_index = kTyreOffset + j;
    const double sigma_j = batch.tyre_fixed_by_car(j) ? batch.car_coefficient(j).sigma
                           : batch.tyre_held(j)       ? batch.tyre_held_sigma(j)
                                                      : sigma(u.params(p_index, p_index));
    summary.parameters.push_back(
        {tyre_parameter_name(kTyreCoefficients[static_cast<std::size_t>(j)]), p[p_index], sigma_j,
         batch.tyre_in_fit(j), true, ""});
    const double rms = batch.regressor_rms()(j);
    thresholds.push_back(rms > 0.0 ? b.max_sigma_tyre_effect / rms : 0.0);
    block_used.push_back(rms > 0.0);
  }
  if (batch.tyre_fitted()) summary.tyre_model = batch.tyre_model();
  std::vector<std::string> problems;
  for (std::size_t i = 0; i < summary.parameters.size(); ++i) {
    EstimatedParameter& parameter = summary.parameters[i];
    if (!parameter.estimated) {
      parameter.sigma = 0.0;
      continue;
    }
    const int coefficient = static_cast<int>(i) - 8;
    if (i >= 8 && batch.tyre_fixed_by_car(coefficient)) {  // the car's, not the log's to identify
      parameter.verdict =
          "held at zero: the rear wheels roll free (vehicle.yaml body.drivetrain: "
          "front), its spread the model's slop";
      continue;
    }
    parameter.identified =
        std::isfinite(parameter.sigma) && parameter.sigma <= thresholds[i] && block_used[i];
    if (!parameter.identified) {
      parameter.verdict = unidentified_reason(parameter.name, coverage, block_used[i]);
      const bool considered =
          i < 2 && (summary.body_sigma_m[i] > 0.0 || summary.held_sigma_m[i] > 0.0);
      const bool extrapolated =
          i < 2 && batch.tyre_fitted() && (!batch.tyre_model().plain() || considered);
      if (extrapolated) {
        parameter.verdict = extrapolation_verdict(summary, i, parameter.sigma, spread[i],
                                                  batch.speed_intervals() > 0);
      } else if (i < 2 && spread[i] > 0.0) {
        parameter.verdict = plain_gap_verdict(parameter.sigma, spread[i]);
      }
      const double misfit = summary.misfit_sigma_scale;
      if (i < 2 && misfit > 1.0) {
        const auto k = static_cast<Eigen::Index>(i);
        const double widened = data_covariance(k, k) * (1.0 - 1.0 / (misfit * misfit));
        // Identified but for the misfit's widening: that is the reason, not the log's coverage.
        if (parameter.sigma * parameter.sigma - widened <= thresholds[i] * thresholds[i]) {
          parameter.verdict = misfit_verdict(summary);
        } else if (!extrapolated) {
          parameter.verdict += fmt::format(
              "; and its sigma is widened {:.2g} times by the model's misfit (chi2/dof {:.3g})",
              misfit, summary.model_adequacy.chi2_per_dof);
        }
      }
      if (i >= 8 && batch.tyre_held(coefficient)) {
        const double held = batch.tyre_held_value(coefficient);
        parameter.verdict = (held == 0.0 ? std::string("held at zero: ")
                                         : fmt::format("held at a car's value, {:.3g}: ", held)) +
                            parameter.verdict;
      }
      problems.push_back(parameter.name + ": " + parameter.verdict);
    }
  }
  summary.covariance = u.params.topLeftCorner<2, 2>();
  summary.params_covariance =
      uncertainty ? u.params.topLeftCorner<3, 3>().eval() : Eigen::Matrix3d::Constant(inf);
  if (b.estimate_track_width && uncertainty) {
    summary.odometry_scales =
        odometry_scales(log.vehicle.nominal_params(), summary.estimate, summary.params_covariance);
  }
  if (uncertainty) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(summary.covariance);
    summary.condition_number =
        std::sqrt(eigen.eigenvalues()(1) / std::max(eigen.eigenvalues()(0), 1e-300));
  } else {
    summary.condition_number = inf;
    summary.covariance.setConstant(inf);
    problems.insert(problems.begin(), kRankDeficientReason);
  }
  summary.identifiability = problems.empty()
                                ? "every requested parameter identified"
                                : fmt::format("not identified: {}", fmt::join(problems, "; "));
  if (!batch.tyre_fitted()) suggest_tyre_model(summary.model_adequacy);
  summary.solver_report = solver.BriefReport();
  summary.gentle_limits = b.gentle_max_speed_mps > 0.0 || b.gentle_max_longitudinal_mps2 > 0.0 ||
                          b.gentle_max_lateral_mps2 > 0.0;
  std::tie(summary.odometry_intervals_used, summary.odometry_intervals) = batch.gentle_intervals();
  summary.keyframes = batch.keyframes();
  summary.gnss_fixes = batch.gnss_residuals();
  summary.doppler_intervals = batch.speed_intervals();

  const std::string doppler =
      summary.doppler_intervals == 0 ? ""
      : summary.doppler_sigma_scale > 1.0
          ? fmt::format(
                " and the Doppler speed over {} intervals (its noise {:.2g} times the "
                "configured, as its residuals show)",
                summary.doppler_intervals, summary.doppler_sigma_scale)
          : fmt::format(" and the Doppler speed over {} intervals", summary.doppler_intervals);
  const std::string solved =
      fmt::format("batch maximum likelihood over {} keyframes and {} GNSS fixes{}; {} solve(s); {}",
                  summary.keyframes, summary.gnss_fixes, doppler, summary.solves,
                  ceres::TerminationTypeToString(solver.termination_type));
  if (batch.tyre_fitted() && !batch.tyre_model().plain() && uncertainty) {
    summary.reference_circumference = reference_circumference(
        batch, p, data_covariance, b.reference_speed_mps, b.max_sigma_circumference_m);
  }
  const bool circumferences_identified =
      uncertainty && summary.parameters[0].identified && summary.parameters[1].identified;
  if (solver.termination_type == ceres::NO_CONVERGENCE) {
    summary.termination = Termination::kNoConvergence;
    summary.message =
        fmt::format("{}: the solver reached max_solver_iterations ({}) before converging", solved,
                    b.max_solver_iterations);
  } else if (!solver.IsSolutionUsable()) {
    summary.termination = Termination::kFailure;
    // Ceres' message can span lines and name memory addresses; its first line says what failed.
    summary.message =
        fmt::format("{}: {}", solved, solver.message.substr(0, solver.message.find('\n')));
  } else if (!circumferences_identified) {
    summary.termination = Termination::kNotIdentifiable;
    summary.message =
        fmt::format("{}: {}", solved,
                    circumference_refusal(summary.parameters, b.max_sigma_circumference_m,
                                          !uncertainty.has_value()));
  } else {
    summary.message = solved;
  }
}

// Solves until the parameters stop moving by more than relinearise_relative_change (at most
// max_relinearisations times again) and the robust loss's weights by more than
// kWeightTolerance. Re-weighting is a majorise-minimise iteration that creeps where many fixes
// sit on the loss's slope (a model that does not fit the log): up to kMaxReweightings solves
// more reach the robust estimate the whole-problem solve would (within 0.05 mm on the realistic
// Hockenheim drive; three stopped 1.3 mm short). A round that only re-weights keeps the driving
// state: measuring it again and again from the model being fitted walks the tyre coefficients
// off (8 sigma in TyreModelBatch.RecoversKnownCoefficientsWhereThePlainModelIsBiased).
//
// With `wandered`, re-weighting also stops where it does not settle, and says so: a step no
// smaller than the one two solves before, after the last re-linearisation.
ceres::Solver::Summary solve_relinearised(BatchProblem& batch, const BatchOptions& options,
                                          BatchSummary& summary, bool* wandered = nullptr) {
  constexpr double kWeightTolerance = 0.01;
  constexpr int kMaxReweightings = 20;
  const int before = summary.solves;
  ceres::Solver::Summary solver;
  constexpr double kCoarseNoise = 1e-3;  // m per sqrt(m), slip and lateral
  bool relinearise = true;
  // Re-weighting that creeps moves on from solve to solve. One that returns to where it was two
  // solves before alternates between two solutions (a model far from the log: the physical tyre
  // terms on a skid-steer robot), and more rounds only repeat them (the Husky bag: 20 rounds of a
  // two-cycle, three times over, in one tyre_model auto).
  batch::ParamsVector last(batch.params().data()), before_last = last;
  double last_step = std::numeric_limits<double>::infinity(), step_before_last = last_step;
  if (wandered) *wandered = false;
  while (true) {
    batch.preintegrate_all(summary.solves == 0 ? kCoarseNoise : 0.0, relinearise);
    const bool reweighted = batch.max_weight_change() > kWeightTolerance;
    solver = batch.solve();
    ++summary.solves;
    const int again = summary.solves - before;
    const double step = batch.change_from(last);
    const bool alternating = !relinearise && step > options.relinearise_relative_change &&
                             batch.change_from(before_last) < 0.1 * step;
    const bool wandering = wandered && !relinearise && step > options.relinearise_relative_change &&
                           step >= 0.9 * step_before_last;
    before_last = std::exchange(last, batch::ParamsVector(batch.params().data()));
    step_before_last = std::exchange(last_step, step);
    if (wandering) *wandered = true;
    if (summary.solves == 1) continue;
    relinearise = batch.relative_change() > options.relinearise_relative_change &&
                  again <= options.max_relinearisations;
    const bool reweight = reweighted && !alternating && !wandering &&
                          again <= options.max_relinearisations + kMaxReweightings;
    if (!relinearise && !reweight) break;
  }
  return solver;
}

// The largest coefficient's effect at the log's RMS driving state, relative to kMaxTyreEffect's
// 3 % of circumference; the side slip's (rad) counts against kMaxSideSlipRad instead.
double max_tyre_effect(const BatchProblem& batch) {
  TyreModel::Vector effect =
      batch.tyre_model().coefficients().cwiseProduct(batch.regressor_rms()).cwiseAbs();
  effect(kSideSlipCoefficient) *= batch::kMaxTyreEffect / batch::kMaxSideSlipRad;
  return effect.maxCoeff();
}

// Whether adapt_gnss_noise measures how much the adaptation widened the circumferences' sigma
// (two marginal covariances; a judge that only reads the residuals does without).
enum class SigmaInflation { kMeasure, kSkip };

// The GNSS error in the solution's residuals; when it differs from the configured noise (a
// correlated part, or a white level off by more than 25 %), the problem is solved again with it,
// and again with what that solution's residuals show (a fit that trusts GNSS too much hides part
// of its error in the trajectory), until the noise estimate settles. The report says by how much
// that widened the circumferences' sigma.
void adapt_gnss_noise(BatchProblem& batch, const BatchOptions& options,
                      const CalibrationOptions& common, BatchSummary& summary,
                      ceres::Solver::Summary& solver,
                      SigmaInflation inflation = SigmaInflation::kMeasure) {
  GnssNoiseReport& report = summary.gnss_noise;
  report.configured_sigma_m = batch.gnss_sigma_rms_m();
  GnssNoiseEstimate noise = estimate_gnss_noise(batch.gnss_errors());
  report.residual_sigma_m = noise.total_sigma_m;
  report.white_sigma_m = noise.white_sigma_m;
  report.gauss_markov_sigma_m = noise.gauss_markov_sigma_m;
  report.gauss_markov_tau_s = noise.gauss_markov_tau_s;
  // A correlated error carried over from another fit's adaptation (tyre_model_selection.cpp) is
  // that fit's answer already.
  const bool carried = batch.noise_adapted() && batch.gauss_markov();
  if (!options.adapt_gnss_noise || carried || noise.fixes == 0 || !solver.IsSolutionUsable())
    return;
  const double configured = report.configured_sigma_m;
  // A stated correlated error stands where the residuals show no more of one (they show less:
  // its states and the trajectory take part of it), and is the least the adapted model keeps:
  // stated 0.5 m under 2 m over 60 s, the adaptation had been off, and 4 of 20 circumferences
  // of the ideal urban drive fell outside 3 sigma (docs/batch-calibration.md, "Not seen yet").
  const double stated_sigma_m = batch.gauss_markov() ? batch.gauss_markov_sigma_m() : 0.0;
  const double stated_tau_s = batch.gauss_markov_tau_s();
  const double white_ratio = noise.white_sigma_m / batch.white_gnss_sigma_rms_m();
  if (noise.gauss_markov_sigma_m <= 1.25 * stated_sigma_m && white_ratio > 0.8 &&
      white_ratio < 1.25)
    return;
  const auto set_noise = [&](double gm_sigma_m, double gm_tau_s) {
    if (gm_sigma_m < stated_sigma_m) {
      gm_sigma_m = stated_sigma_m;
      gm_tau_s = stated_tau_s;
    }
    batch.set_gnss_noise(noise.white_sigma_m / configured, gm_sigma_m, gm_tau_s);
  };
  const bool measure = inflation == SigmaInflation::kMeasure;
  const auto before = measure ? batch.uncertainty() : std::nullopt;
  // Where the first estimate stands again, it is put back as it was: solved again from where an
  // adapted solve ran away, the regression terms went to 1e38 and c_RL to -9e16 m (3 laps of
  // Hockenheim's racing line, rear-driven, seed 7).
  const BatchProblem::Solution first_solution = batch.solution();
  const ceres::Solver::Summary first_solver = solver;
  const double first_tyre_effect = max_tyre_effect(batch);
  constexpr int kMaxRounds = 4;
  // What the data can support: a few times the first fit's residuals. Beyond, the error model
  // would explain the odometry's own misfit (a vehicle the two-wheel model does not describe)
  // as GNSS error, let the trajectory float free of GNSS and feed on itself.
  const double bound_m = 3.0 * noise.total_sigma_m;
  for (int round = 0; round < kMaxRounds; ++round) {
    set_noise(noise.gauss_markov_sigma_m, noise.gauss_markov_tau_s);
    solver = solve_relinearised(batch, options, summary);
    const GnssNoiseEstimate next = estimate_gnss_noise(batch.gnss_errors());
    const auto settled = [](double a, double b) { return std::abs(a - b) <= 0.1 * std::max(a, b); };
    const bool done = settled(next.white_sigma_m, noise.white_sigma_m) &&
                      settled(next.gauss_markov_sigma_m, noise.gauss_markov_sigma_m) &&
                      settled(next.gauss_markov_tau_s, noise.gauss_markov_tau_s);
    if (next.total_sigma_m > bound_m) break;  // running away: keep the model solved with
    noise = next;
    if (done || !solver.IsSolutionUsable()) break;
  }
  report.adapted = true;
  report.residual_sigma_m = noise.total_sigma_m;
  report.white_sigma_m = noise.white_sigma_m;
  report.gauss_markov_sigma_m = noise.gauss_markov_sigma_m;
  report.gauss_markov_tau_s = noise.gauss_markov_tau_s;
  report.model_gauss_markov_sigma_m = batch.gauss_markov_sigma_m();
  report.model_gauss_markov_tau_s = batch.gauss_markov() ? batch.gauss_markov_tau_s() : 0.0;
  // A fit that trusted GNSS followed its slow error in the trajectory, so the residuals show a
  // short correlation time; their random-walk intensity (sigma^2 / tau) is kept over at least a
  // tenth of the log. Not capped by the first fit's scatter: on a 2 m drift over 60 s that the
  // first fit hid (residuals 0.33 m), the cap modelled 0.99 m and the sigma fell to 0.6 times the
  // Cramer-Rao sigma (bench/honest_sigma.cpp: 87.5 % inside 3 sigma, 100 % without the cap).
  const double min_tau_s = 0.1 * batch.duration_s();
  const double stretched_sigma_m =
      noise.gauss_markov_tau_s > 0.0
          ? noise.gauss_markov_sigma_m * std::sqrt(min_tau_s / noise.gauss_markov_tau_s)
          : 0.0;
  if (noise.gauss_markov_sigma_m > 0.0 && noise.gauss_markov_tau_s < min_tau_s &&
      stretched_sigma_m > stated_sigma_m) {
    set_noise(stretched_sigma_m, min_tau_s);
    report.model_gauss_markov_sigma_m = batch.gauss_markov_sigma_m();
    report.model_gauss_markov_tau_s = batch.gauss_markov_tau_s();
    solver = solve_relinearised(batch, options, summary);
  }
  // The circumferences' sigma at the current solution over the first's; none where either could
  // not be computed.
  const auto inflation_since_first = [&]() -> std::optional<double> {
    const auto after = measure ? batch.uncertainty() : std::nullopt;
    if (!before || !after) return std::nullopt;
    return std::sqrt(after->params.topLeftCorner<2, 2>().trace() /
                     before->params.topLeftCorner<2, 2>().trace());
  };
  const std::optional<double> at_adapted = inflation_since_first();
  if (at_adapted) report.sigma_inflation = *at_adapted;
  // The adaptation changes weights; it must not carry a plausible estimate out of the plausible
  // band (GNSS weighted down so far that a misfit of the odometry model decides), nor a tyre model
  // into coefficients that are no tyre (on a circuit's hard braking, GNSS loosened to a metres-
  // wide correlated error let k_speed reach -4e-4 per (m/s)^2: -100 % at 50 m/s). Then the first
  // estimate stands, with its covariance under the adapted noise model.
  const auto implausible = [&](double c_rl, double c_rr) {
    return std::max(std::abs(c_rl / summary.nominal.circumference_rl_m - 1.0),
                    std::abs(c_rr / summary.nominal.circumference_rr_m - 1.0)) >
           common.max_relative_change;
  };
  const bool tyre_ran_away =
      max_tyre_effect(batch) > batch::kMaxTyreEffect && first_tyre_effect <= batch::kMaxTyreEffect;
  if ((implausible(batch.params()[0], batch.params()[1]) &&
       !implausible(first_solution.unknowns.params[0], first_solution.unknowns.params[1])) ||
      tyre_ran_away) {
    // Not solved again: from the first estimate, the relinearised solve walks on (this log's
    // regression terms: c_RL from -60 to +24 mm of nominal). Its widening is measured there,
    // under the adapted noise: at the solution that ran away it could not always be computed,
    // and the first sigma then went unwidened (0.2 mm on the plain fit of the same log, 70 mm
    // off). Where it cannot be computed at either, the sigma is not known.
    report.reverted = true;
    batch.return_to(first_solution);
    const auto rebuild = [&] {
      batch.preintegrate_all(0.0, false);
      batch.build();
    };
    rebuild();
    const std::optional<double> at_first = inflation_since_first();
    if (at_first) report.sigma_inflation = *at_first;
    report.covariance_scale = at_first || at_adapted || !measure
                                  ? report.sigma_inflation * report.sigma_inflation
                                  : std::numeric_limits<double>::infinity();
    batch.restore_configured_gnss_noise();
    rebuild();
    solver = first_solver;
  }
}

// The Doppler residuals' scatter (the RMS of the whitened residuals): where it is wider
// than the configured noise (a receiver noisier than gnss_speed_sigma_mps, or a slip that the
// tyre model does not follow), the problem is solved again with the noise it shows, so that the
// Doppler speed weighs what it is worth beside the positions. Never narrowed: a receiver's
// velocity errors are correlated over its filter, which one interval's residual does not show.
void adapt_doppler_noise(BatchProblem& batch, const BatchOptions& options, BatchSummary& summary,
                         ceres::Solver::Summary& solver) {
  constexpr int kMaxRounds = 4;
  constexpr double kTolerance = 1.25;
  for (int round = 0; round < kMaxRounds && solver.IsSolutionUsable(); ++round) {
    const std::vector<double> whitened = batch.speed_whitened();
    if (whitened.empty()) break;
    double sum = 0.0;
    for (const double r : whitened) sum += r * r;
    const double spread = std::sqrt(sum / static_cast<double>(whitened.size()));
    if (!(spread > kTolerance)) break;
    batch.set_speed_noise(batch.speed_noise_scale() * spread);
    solver = solve_relinearised(batch, options, summary);
  }
  summary.doppler_sigma_scale = batch.speed_noise_scale();
}

// A coefficient this many sigma from zero is kept however wide its sigma: the log needs it, and
// held at zero the others would bend to stand in for it.
constexpr double kTyreSignificance = 3.0;

// A tyre model's family of terms with what this log can identify: a coefficient whose sigma
// exceeds its threshold is held at zero and the rest solved again (a drive at one speed cannot
// tell k_speed from the circumference; left free, it would carry the circumference's sigma away
// with it).
// Tyre coefficient j's variance in `uncertainty`; -1 where there is none (singular information).
double tyre_variance(const std::optional<BatchProblem::Uncertainty>& uncertainty, int j) {
  return uncertainty ? uncertainty->params(kTyreOffset + j, kTyreOffset + j) : -1.0;
}

ceres::Solver::Summary solve_tyre_model(BatchProblem& batch, const BatchOptions& options,
                                        BatchSummary& summary, TyreTerms terms) {
  batch.set_tyre_terms(terms);
  // Never free: left free, the drive slip of a free-rolling axle takes up what the heading and
  // the GNSS noise make of it, and the circumferences follow (the built-in circuit, front-driven:
  // +3.3 mm at sigma 1.2 mm). Held at zero, as where the log says nothing, its spread there the
  // car's (tyre_car_prior.hpp) goes into their sigma.
  if (batch.tyre_fixed_by_car(kDriveSlipCoefficient))
    batch.hold_tyre_coefficient(kDriveSlipCoefficient, std::numeric_limits<double>::infinity());
  bool wandered = false;
  ceres::Solver::Summary solver = solve_relinearised(batch, options, summary, &wandered);
  if (wandered && solver.IsSolutionUsable()) {
    // Coefficients whose fit does not settle are not what this log identifies: all of them are
    // held at zero (the Husky bag's regression terms wandered by up to 700 times the
    // circumference at its driving state; stopped where they stood, a fit that kept one of them
    // moved the circumference 21 mm). Their sigma is the one where the fit stopped.
    const auto uncertainty = batch.uncertainty();
    for (int j = 0; j < TyreModel::kCoefficients; ++j) {
      if (!batch.tyre_in_fit(j) || batch.tyre_held(j)) continue;
      const double variance = tyre_variance(uncertainty, j);
      batch.hold_tyre_coefficient(
          j, variance > 0.0 ? std::sqrt(variance) : std::numeric_limits<double>::infinity(),
          BatchProblem::FreeValue::kWandered);
    }
    batch.restart();
    return solve_relinearised(batch, options, summary);
  }
  for (int round = 0; round < TyreModel::kCoefficients && solver.IsSolutionUsable(); ++round) {
    const auto uncertainty = batch.uncertainty();
    // The coefficients the log does not identify, each with its sigma while free.
    std::vector<std::pair<int, double>> unidentified;
    for (int j = 0; j < TyreModel::kCoefficients; ++j) {
      if (!batch.tyre_in_fit(j) || batch.tyre_held(j)) continue;
      const double variance = tyre_variance(uncertainty, j);
      const double sigma = variance >= 0.0 ? std::sqrt(variance) : 0.0;
      const double rms = batch.regressor_rms()(j);
      const double value = batch.params()[static_cast<std::size_t>(kTyreOffset + j)];
      const bool significant = std::abs(value) > kTyreSignificance * sigma;
      if (!(variance >= 0.0) || !(rms > 0.0) ||
          (sigma * rms > options.max_sigma_tyre_effect && !significant)) {
        unidentified.emplace_back(j, std::isfinite(sigma) && sigma > 0.0
                                         ? sigma
                                         : std::numeric_limits<double>::infinity());
      }
    }
    if (unidentified.empty()) break;
    // All at once, but the side slip alone first: it turns the course, not the wheels, and an
    // unidentified side slip widens the sigma of the slip terms it is correlated with, which are
    // identified without it (on the urban drive the brake slip went with it: c_RL 7.5 mm off).
    // Held one by one otherwise, the regression terms of a skid-steer robot ran away.
    const auto side_slip = std::find_if(unidentified.begin(), unidentified.end(),
                                        [](auto& u) { return u.first == kSideSlipCoefficient; });
    if (side_slip != unidentified.end()) unidentified = {*side_slip};
    for (const auto& [j, sigma] : unidentified) batch.hold_tyre_coefficient(j, sigma);
    batch.restart();
    solver = solve_relinearised(batch, options, summary);  // without what was just held
    if (batch.free_tyre_coefficients() == 0) break;
  }
  // Held at zero while deciding, as the plain model would; then at a car's value, a better guess
  // than zero for a coefficient whose sign and size are the physics' (urban drive, seed 8: the
  // brake slip held at zero put c_RL 10 mm off, at a car's 0.0175 1.4 mm).
  if (solver.IsSolutionUsable() && batch.hold_at_car_values()) {
    batch.restart();
    solver = solve_relinearised(batch, options, summary);
  }
  return solver;
}

}  // namespace

bool batch::fit_model(const CalibrationRun& run, const BatchOptions& options,
                      const CalibrationOptions& common, std::optional<TyreTerms> terms,
                      BatchSummary& summary, const FitDecision& finish,
                      const std::optional<std::array<double, 2>>& rival_circumference,
                      const std::optional<GnssNoiseModel>& noise) {
  BatchProblem batch(run.log(), run.reference(), options, common, summary.nominal);
  if (noise) {
    batch.set_gnss_noise(noise->white_scale, noise->gauss_markov_sigma_m,
                         noise->gauss_markov_tau_s);
  }
  const bool extended = terms.has_value();
  ceres::Solver::Summary solver = extended ? solve_tyre_model(batch, options, summary, *terms)
                                           : solve_relinearised(batch, options, summary);
  const auto spread = [&] {
    std::array<double, 2> gap{};
    if (rival_circumference) {
      for (std::size_t w = 0; w < 2; ++w)
        gap[w] = std::abs(batch.params()[w] - (*rival_circumference)[w]);
    }
    return gap;
  };
  batch.set_model_spread(spread());
  if (finish) {
    batch::FitFacts facts;
    if (solver.IsSolutionUsable()) {
      facts.usable = true;
      facts.bic = batch.information_criterion(solver);
      facts.free_tyre_coefficients = batch.free_tyre_coefficients();
      facts.max_tyre_effect = max_tyre_effect(batch);
      facts.circumference = {batch.params()[0], batch.params()[1]};
      if (extended) {
        const std::array<double, 2>& gap = batch.model_spread_m();
        if (const auto u = batch.uncertainty())
          facts.circumference_variance = {u->params(0, 0) + gap[0] * gap[0],
                                          u->params(1, 1) + gap[1] * gap[1]};
      }
    }
    if (!finish(facts)) return false;
  }
  adapt_doppler_noise(batch, options, summary, solver);
  adapt_gnss_noise(batch, options, common, summary, solver);
  batch.set_model_spread(spread());  // at the solution reported
  batch.add_considered_uncertainty();
  summarise(run.log(), options, batch, solver, summary);
  return true;
}

batch::ModelJudgement batch::judge_model_adequacy(const CalibrationRun& run,
                                                  const OdometryParams& start,
                                                  const CalibrationOptions& common) {
  // The plain model (no tyre terms are given) with the batch's defaults (its 1 s keyframes, its
  // noises), its GNSS noise adapted as its own fit's is: under a configured sigma far above the
  // receiver's the poses follow the wheels and hide their slip (comma2k19: 3 m configured,
  // 0.13 m found).
  const BatchOptions options;
  BatchSummary scratch;
  scratch.nominal = run.log().vehicle.nominal_params();
  const BatchSummary unfitted = scratch;
  ModelJudgement judgement;
  double plain_bic = 0.0;
  {
    BatchProblem batch(run.log(), run.reference(), options, common, start);
    ceres::Solver::Summary solver = solve_relinearised(batch, options, scratch);
    if (solver.IsSolutionUsable()) plain_bic = batch.information_criterion(solver);
    adapt_gnss_noise(batch, options, common, scratch, solver, SigmaInflation::kSkip);
    if (!solver.IsSolutionUsable()) {
      judgement.adequacy.verdict =
          fmt::format("not judged: the batch pose graph did not solve ({})",
                      ceres::TerminationTypeToString(solver.termination_type));
      return judgement;
    }
    judgement.adequacy = assess_model_adequacy(batch.odometry_errors());
  }  // freed before the tyre models' problems
  ModelAdequacy& adequacy = judgement.adequacy;
  suggest_tyre_model(adequacy);
  const TyreJudgement tyre =
      judge_against_tyre_models(run, options, common, unfitted, scratch.gnss_noise, plain_bic);
  if (tyre.circumference) {
    judgement.gap_m = {std::abs(start.circumference_rl_m - (*tyre.circumference)[0]),
                       std::abs(start.circumference_rr_m - (*tyre.circumference)[1])};
    say_a_tyre_model_fits_better(adequacy, tyre, judgement.gap_m, "this estimate's");
  }
  // Said, so that the residuals are not taken for the other method's.
  adequacy.verdict += " [judged on a batch fit of this log]";
  return judgement;
}

BatchSummary calibrate_batch(const Log& log, const BatchOptions& options,
                             const CalibrationOptions& common) {
  require_valid("batch", options.validate());
  BatchSummary summary;
  CalibrationRun run(log, common, CalibrationMethod::kBatch, summary);
  // The Doppler fit reads the column (the reference has judged it already where it reads it too).
  if (options.doppler_sigma_mps(!run.log().gnss.speed_mps.empty()) > 0.0 &&
      !common.reference.use_gnss_speed)
    check_doppler_scale(run.log(), summary.nominal);
  bool finished = false;  // auto scores its candidates itself
  if (options.tyre_model == TyreModelChoice::kAuto) {
    finished = batch::fit_auto(run, options, common, summary);
  } else if (options.tyre_model == TyreModelChoice::kNone && common.judge_model_adequacy) {
    batch::fit_plain_judged(run, options, common, summary);
  } else {
    const std::optional<TyreTerms> terms =
        options.tyre_model == TyreModelChoice::kExtended   ? std::optional(TyreTerms::kRegression)
        : options.tyre_model == TyreModelChoice::kPhysical ? std::optional(TyreTerms::kPhysical)
                                                           : std::nullopt;
    batch::fit_model(run, options, common, terms, summary);
  }
  if (!finished) run.finish(summary);
  return summary;
}

std::string BatchSummary::full_report() const {
  std::string text = report_heading(*this);
  for (const EstimatedParameter& p : parameters) {
    if (!p.estimated || p.name.starts_with("circumference")) continue;
    text += fmt::format("{:<13}{} = {:.6g} (1-sigma {:.3g}{}{})\n", "parameter", p.name, p.value,
                        p.sigma, p.identified && !p.verdict.empty() ? "; " : "",
                        p.identified ? p.verdict : "");
  }
  text += fmt::format("{:<13}{}\n", "observable", identifiability);
  if (odometry_scales) {
    const OdometryScales& s = *odometry_scales;
    text += fmt::format(
        "{:<13}speed x{:.4f} (1-sigma {:.4f}), yaw rate x{:.4f} (1-sigma {:.4f}) against the "
        "nominal model\n",
        "odometry", s.speed_scale, s.sigma_speed_scale, s.yaw_rate_scale, s.sigma_yaw_rate_scale);
  }
  const GnssNoiseReport& g = gnss_noise;
  if (g.adapted) {
    text += fmt::format(
        "{:<13}residuals {:.3g} m RMS where {:.3g} m was configured: solved again with white "
        "{:.3g} m{}; sigma x{:.2f}\n",
        "gnss noise", g.residual_sigma_m, g.configured_sigma_m, g.white_sigma_m,
        g.gauss_markov_sigma_m > 0.0
            ? fmt::format(" and a correlated {:.3g} m over {:.0f} s (modelled as {:.3g} m over "
                          "{:.0f} s)",
                          g.gauss_markov_sigma_m, g.gauss_markov_tau_s,
                          g.model_gauss_markov_sigma_m, g.model_gauss_markov_tau_s)
        : g.model_gauss_markov_sigma_m > 0.0
            ? fmt::format(" and the stated correlated {:.3g} m over {:.0f} s",
                          g.model_gauss_markov_sigma_m, g.model_gauss_markov_tau_s)
            : std::string(),
        g.sigma_inflation);
    if (g.reverted) {
      text += fmt::format(
          "{:<13}that estimate left the plausible band: the first one stands, its sigma x{:.2f}\n",
          "", g.sigma_inflation);
    }
  } else if (g.residual_sigma_m > 0.0) {
    text += fmt::format("{:<13}residuals {:.3g} m RMS, as configured ({:.3g} m)\n", "gnss noise",
                        g.residual_sigma_m, g.configured_sigma_m);
  }
  if (gentle_limits) {
    text += fmt::format(
        "{:<13}{} of {} keyframe intervals inside the limits feed the odometry ({:.0f} %)\n",
        "gentle", odometry_intervals_used, odometry_intervals,
        100.0 * static_cast<double>(odometry_intervals_used) /
            static_cast<double>(std::max<std::size_t>(odometry_intervals, 1)));
  }
  text += batch::tyre_selection_report(*this);
  if (reference_circumference) {
    const ReferenceCircumference& r = *reference_circumference;
    text += fmt::format(
        "{:<13}c_RL {:.6f} m (1-sigma {:.3f} mm), c_RR {:.6f} m (1-sigma {:.3f} mm) rolling "
        "straight at a steady {:g} m/s, slip and load included{}\n",
        "rolling", r.circumference_rl_m, 1e3 * r.sigma_rl_m, r.circumference_rr_m,
        1e3 * r.sigma_rr_m, r.speed_mps, r.identified ? "" : ": not identified");
  }
  if (body_sigma_m[0] > 0.0 || body_sigma_m[1] > 0.0) {
    std::vector<std::string> assumed;
    for (const BodyUncertainty& u : kBodyUncertainties) assumed.push_back(u.text());
    // The number worth measuring first: the one whose uncertainty moves the circumferences most.
    const auto largest = std::max_element(
        body_sigma_parts.begin(), body_sigma_parts.end(), [](const auto& a, const auto& b) {
          return std::max(a.sigma_m[0], a.sigma_m[1]) < std::max(b.sigma_m[0], b.sigma_m[1]);
        });
    const std::string most =
        largest == body_sigma_parts.end()
            ? ""
            : fmt::format("; most of it {}'s, {:.3g} / {:.3g} mm", largest->key,
                          1e3 * largest->sigma_m[0], 1e3 * largest->sigma_m[1]);
    text += fmt::format(
        "{:<13}the circumferences' sigma includes {:.3g} / {:.3g} mm from the body's uncertainty "
        "(vehicle.yaml body: {}{})\n",
        "body", 1e3 * body_sigma_m[0], 1e3 * body_sigma_m[1], fmt::join(assumed, ", "), most);
  }
  if (held_sigma_m[0] > 0.0 || held_sigma_m[1] > 0.0) {
    std::vector<std::string> parts;
    for (const HeldSigmaPart& part : held_sigma_parts) {
      parts.push_back(fmt::format("{} +-{:.2g}: {:.3g} / {:.3g} mm", part.key,
                                  part.coefficient_sigma, 1e3 * part.sigma_m[0],
                                  1e3 * part.sigma_m[1]));
    }
    text += fmt::format(
        "{:<13}the circumferences' sigma includes {:.3g} / {:.3g} mm from the tyre coefficients "
        "held, that this log cannot identify or the car fixes: each where a car's value and the "
        "log's own word put it (a regression term, which no car sizes, at zero with the log's "
        "word for its spread; at zero where its fit wandered or the rear wheels roll free), and "
        "its spread there ({})\n",
        "held", 1e3 * held_sigma_m[0], 1e3 * held_sigma_m[1], fmt::join(parts, ", "));
  }
  if (model_spread_m[0] > 0.0 || model_spread_m[1] > 0.0) {
    text += fmt::format(
        "{:<13}the circumferences' sigma includes {:.3g} / {:.3g} mm, their gap to {}\n", "spread",
        1e3 * model_spread_m[0], 1e3 * model_spread_m[1],
        tyre_selection.judges_plain
            ? "a tyre model's fit of this log (the tyre model line names it): the plain "
              "circumferences are the ones this drive rolled on, slip and load in them, not the "
              "ones at rest"
            : "the physical terms' fit of this log: the regression terms extrapolate to rest no "
              "surer than the two models agree");
  }
  text += fmt::format("{:<13}{}\n", "solver", usable() ? message : solver_report);
  return text + report_ending(*this);
}

}  // namespace odocal
