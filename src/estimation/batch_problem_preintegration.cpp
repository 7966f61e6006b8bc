// BatchProblem's measurements at the current unknowns: the wheels pre-integrated per keyframe
// interval, the GNSS fixes and heading samples folded into one residual per interval, the
// Doppler speed against the wheels, and every residual read back for the model-adequacy checks.
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "batch_problem.hpp"

namespace odocal::batch {
namespace {

// The segment's Jacobian at sample s with respect to every parameter.
batch::ParamsJacobian params_jacobian(const PreintegratedSegment& segment, std::size_t s) {
  batch::ParamsJacobian J = batch::ParamsJacobian::Zero();
  J.leftCols<3>() = segment.J_delta_params[s];
  if (!segment.J_delta_tyre.empty())
    J.rightCols<TyreModel::kCoefficients>() = segment.J_delta_tyre[s];
  return J;
}

// The mean of a per-sample column over the increments of samples (from, to].
double interval_mean(const std::vector<float>& column, std::size_t from, std::size_t to) {
  double sum = 0.0;
  for (std::size_t k = from + 1; k <= to; ++k) sum += column[k];
  return to > from ? sum / static_cast<double>(to - from) : column[from];
}

}  // namespace

GnssResidualSource BatchProblem::gnss_errors() const {
  return [this](const GnssResidualSink& sink) {
    for_each_fix([&](std::size_t fix, std::size_t segment, const Eigen::Vector2d& whitened) {
      Eigen::Vector2d error = -white_gnss_sigma(fix) * whitened;
      if (gauss_markov()) error += Eigen::Vector2d(gnss_bias_[segment][0], gnss_bias_[segment][1]);
      sink(log_.gnss.t_s[fix], error);
    });
  };
}

std::vector<OdometryResidualSample> BatchProblem::odometry_errors() const {
  std::vector<OdometryResidualSample> samples;
  samples.reserve(odometry_blocks_.size());
  for (const OdometryBlock& b : odometry_blocks_) {
    Eigen::Vector3d whitened;
    double cost = 0.0;
    problem_->EvaluateResidualBlock(b.id, false, &cost, whitened.data(), nullptr);
    const std::size_t i = b.segment;
    const Eigen::Matrix3d& sqrt_covariance = odometry_[i].sqrt_covariance;
    OdometryResidualSample sample{
        wheels_.t_s[keyframes_[i]],
        wheels_.t_s[keyframes_[i + 1]],
        Eigen::Vector3d(poses_[i][0], poses_[i][1], poses_[i][2]),
        Eigen::Vector3d(poses_[i + 1][0], poses_[i + 1][1], poses_[i + 1][2]),
        sqrt_covariance * whitened,
        whitened};
    // The grade the preparation projected with (none: not known, and not tested).
    if (!wheels_.grade.empty())
      sample.grade = interval_mean(wheels_.grade, keyframes_[i], keyframes_[i + 1]);
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

void BatchProblem::preintegrate_all(double slip_floor, bool remeasure_states, Folds folds) {
  const bool refold = folds == Folds::kRebuild;
  if (refold) folded_fixes_ = folded_headings_ = 0;
  const OdometryParams at{params_[0], params_[1], params_[2]};
  problem_.reset();  // its blocks point to the folds replaced here; freed before the states
  if (remeasure_states && tyre_fitted() && !tyre_model().plain()) {
    // The driving state from the wheels as the current model counts them: a slipping wheel
    // overstates speed and acceleration by its slip.
    measure_driving_states_again(wheels_, imu(), at, tyre_model(), body_, states_,
                                 kDrivingStateHalfWindowS, batch_.threads);
  }
  const TyreConditions tyre{states_, tyre_model(), body_};
  const WheelNoise noise{std::max(noise_.slip_sigma_m_per_sqrt_m, slip_floor),
                         noise_.quantisation_sigma_rev,
                         std::max(noise_.lateral_sigma_m_per_sqrt_m, slip_floor)};
  params_lin_ = Eigen::Map<const batch::ParamsVector>(params_.data());
  latency_lin_ = latency_;
  const std::size_t intervals = keyframes_.size() > 1 ? keyframes_.size() - 1 : 0;
  odometry_.clear();
  odometry_.resize(intervals);  // each written by its part below
  speed_.assign(intervals, std::nullopt);
  if (refold) {
    folds_.assign(intervals, {});
    max_weight_change_ = 0.0f;
    fold_columns_ = fold_columns();
  }
  // Every interval on its own: the parts write only their own intervals, fixes and tallies.
  const int threads = usable_threads(batch_.threads);
  std::vector<FoldTally> tallies(static_cast<std::size_t>(threads));
  const auto integrate_part = [&](std::size_t part, std::size_t begin, std::size_t end) {
    if (begin == end) return;
    auto [next_fix, next_heading] = cursors_at(begin);
    for (std::size_t i = begin; i < end; ++i) {
      const PreintegratedSegment segment = preintegrate(wheels_, keyframes_[i], keyframes_[i + 1],
                                                        at, noise, tyre_fitted() ? &tyre : nullptr);
      odometry_[i] = odometry_interval(segment);
      if (gap_segment(i)) continue;
      if (use_speed() && rough_segment_[i] == 0) speed_[i] = speed_residual(i, segment, at);
      if (refold) fold_interval(i, segment, next_fix, next_heading, tallies[part]);
    }
  };
  run_in_parts(intervals, threads, integrate_part);
  if (!refold) return;
  for (const FoldTally& tally : tallies) {
    folded_fixes_ += tally.fixes;
    folded_headings_ += tally.headings;
    max_weight_change_ = std::max(max_weight_change_, tally.max_weight_change);
  }
}

std::vector<double> BatchProblem::speed_whitened() const {
  std::vector<double> whitened;
  for (std::size_t i = 0; i < speed_.size(); ++i)
    if (speed_[i]) whitened.push_back(speed_whitened(i));
  return whitened;
}

double BatchProblem::speed_whitened(std::size_t i) const {
  double r = 0.0;
  (*speed_[i])(params_.data(), lever_.data(), &latency_, count_error_[i].data(),
               count_error_[i + 1].data(), &r);
  return r;
}

std::optional<batch::SpeedResidual> BatchProblem::speed_residual(std::size_t i,
                                                                 const PreintegratedSegment& seg,
                                                                 const OdometryParams& at) const {
  // Below this the speed's magnitude is biased by its own noise (and reversing would hide).
  constexpr double kMinSpeedMps = 1.0;
  const double begin = wheels_.t_s[keyframes_[i]], end = wheels_.t_s[keyframes_[i + 1]];
  // The fixes that report the interval's speeds: stamped the latency after it. Taken to first
  // order in the whole latency instead (the speed at each end times it), the urban drive with
  // the fixes 143 ms late and the latency stated put the regression terms' circumference at rest
  // 4.7 mm from the same log's with the stamps put right, at an exact Doppler speed (seed 19): the
  // speed's change over the latency is not its value at one end.
  const auto interval =
      batch::doppler_interval(log_.gnss, begin + latency_lin_, end + latency_lin_, speed_max_gap_s_,
                              std::max(kMinSpeedMps, 5.0 * doppler_sigma_mps_));
  if (!interval) return std::nullopt;
  batch::SpeedResidual r;
  r.latency_lin_s = latency_lin_;
  const TyreModel model = tyre_model();
  const TyreModel::Vector at_k = model.coefficients();
  // The factor to first order about the coefficients the residual is built at (it is rebuilt
  // with them): exact there, and in every coefficient but the slip's divisor.
  const auto add_tyre = [&](const TyreFactor& f, int w, double half_rev) {
    r.half_revolutions[static_cast<std::size_t>(w)] +=
        half_rev * (f.value - 1.0 - f.gradient.dot(at_k));
    r.half_tyre_revolutions.row(w) += half_rev * f.gradient.transpose();
  };
  for (std::size_t k = keyframes_[i] + 1; k <= keyframes_[i + 1]; ++k) {
    const WheelIncrement n = wheels_.increment(k);
    if (n.rev_rl < 0.0 || n.rev_rr < 0.0) return std::nullopt;
    r.half_revolutions[0] += 0.5 * n.rev_rl;
    r.half_revolutions[1] += 0.5 * n.rev_rr;
    if (!tyre_fitted()) continue;
    const std::array<TyreFactor, 2>& factors = seg.tyre_factors[k - seg.first_sample];
    add_tyre(factors[0], 0, 0.5 * n.rev_rl);
    add_tyre(factors[1], 1, 0.5 * n.rev_rr);
    const double half_square = 0.5 * square(side_slip_regressor(states_[k], body_));
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
  if (!batch_.estimate_lever_arm && batch_.lever_arm_x_m == 0.0 && batch_.lever_arm_y_m == 0.0) {
    // Held at zero: the integral alone.
    double distance = 0.0;
    for (std::size_t f = 0; f < interval->fixes.size(); ++f)
      distance += interval->weights_s[f] * log_.gnss.speed_mps[interval->fixes[f]];
    r.shares.push_back({1.0, distance, 0.0, 0.0});
    return r;
  }
  // The wheels' yaw rate over about half a second around each fix: one sample's is quantised (one
  // tick between the wheels in a 50 Hz sample is 0.64 rad/s), the lever turns it into metres per
  // second, and the speed is not linear in it (stated at 1.5 m ahead of the axle, the urban
  // drive's Doppler noise came out 1.4 times the configured and c_RL 1.6 sigma low).
  constexpr double kYawRateHalfWindowS = 0.25;
  const auto time_of = [&](std::size_t k) { return wheels_.t_s[seg.first_sample + k]; };
  const std::size_t last = seg.delta.size() - 1;
  for (std::size_t f = 0; f < interval->fixes.size(); ++f) {
    const std::size_t j = interval->fixes[f];
    const std::size_t s =
        segment_sample(seg, std::clamp(log_.gnss.t_s[j] - latency_lin_, begin, end));
    std::size_t lo = s, hi = s + 1;
    while (lo > 0 && time_of(s) - time_of(lo - 1) <= kYawRateHalfWindowS) --lo;
    while (hi < last && time_of(hi + 1) - time_of(s + 1) <= kYawRateHalfWindowS) ++hi;
    const double yaw_rate = (seg.delta[hi].z() - seg.delta[lo].z()) / (time_of(hi) - time_of(lo));
    // The side slip's regressor over the same samples (each the accelerometer over one increment);
    // without tyre terms there is no side slip.
    double lateral = 0.0;
    if (tyre_fitted()) {
      for (std::size_t m = lo + 1; m <= hi; ++m)
        lateral += side_slip_regressor(states_[seg.first_sample + m], body_);
      lateral /= static_cast<double>(hi - lo);
    }
    r.shares.push_back({interval->weights_s[f], log_.gnss.speed_mps[j], yaw_rate, lateral});
  }
  return r;
}

std::size_t BatchProblem::segment_sample(const PreintegratedSegment& seg, double t_s) const {
  const auto& t = wheels_.t_s;
  const auto first = t.begin() + static_cast<long>(seg.first_sample);
  const auto last = t.begin() + static_cast<long>(seg.last_sample);
  return static_cast<std::size_t>(std::upper_bound(first, last, t_s) - first) - 1;
}

BatchProblem::MotionAt BatchProblem::motion_at(std::size_t i, const PreintegratedSegment& seg,
                                               double t_s) const {
  const auto& t = wheels_.t_s;
  const std::size_t s = segment_sample(seg, t_s);
  const std::size_t k = seg.first_sample + s;
  const double dt = t[k + 1] - t[k];
  const double w = (t_s - t[k]) / dt;
  MotionAt at;
  at.motion.delta = (1.0 - w) * seg.delta[s] + w * seg.delta[s + 1];
  // Block by block: a fix per wheel sample makes this a hot loop.
  at.motion.J_delta_params.leftCols<3>() =
      (1.0 - w) * seg.J_delta_params[s] + w * seg.J_delta_params[s + 1];
  if (!seg.J_delta_tyre.empty()) {
    at.motion.J_delta_params.rightCols<TyreModel::kCoefficients>() =
        (1.0 - w) * seg.J_delta_tyre[s] + w * seg.J_delta_tyre[s + 1];
  }
  at.motion.J_delta_first_increment =
      (1.0 - w) * seg.J_delta_first_increment[s] + w * seg.J_delta_first_increment[s + 1];
  at.motion.params_lin = params_lin_;
  if (rough_segment_[i] != 0) at.motion.J_delta_params.setZero();
  at.velocity = (seg.delta[s + 1].head<2>() - seg.delta[s].head<2>()) / dt;
  return at;
}

Eigen::Vector2d BatchProblem::whitened_fix(std::size_t j, std::size_t i, const MotionAt& at) const {
  const batch::GnssResidual residual{at.motion, at.velocity,
                                     Eigen::Vector2d(log_.gnss.x_m[j], log_.gnss.y_m[j]),
                                     white_gnss_sigma(j)};
  const double* bias = gauss_markov() ? gnss_bias_[i].data() : zero_bias_.data();
  Eigen::Vector2d whitened;
  residual(poses_[i].data(), params_.data(), lever_.data(), &latency_, bias, count_error_[i].data(),
           whitened.data());
  return whitened;
}

void BatchProblem::fold_interval(std::size_t i, const PreintegratedSegment& seg,
                                 std::size_t& next_fix, std::size_t& next_heading,
                                 FoldTally& tally) {
  batch::RowFold<batch::kFoldedColumns> fold;
  const Eigen::Vector2d origin(poses_[i][0], poses_[i][1]);
  visit_fixes(i, seg, log_.gnss.t_s, fix_lag_s(), next_fix, [&](std::size_t j, const MotionAt& at) {
    const float weight = static_cast<float>(robust(whitened_fix(j, i, at).squaredNorm())[1]);
    tally.max_weight_change =
        std::max(tally.max_weight_change, std::abs(weight - gnss_weights_[j]));
    gnss_weights_[j] = weight;
    ++tally.fixes;
    batch::FoldedIntervalResidual::add_fix(
        fold, at.motion, at.velocity, Eigen::Vector2d(log_.gnss.x_m[j], log_.gnss.y_m[j]) - origin,
        white_gnss_sigma(j), weight);
  });
  if (use_heading()) {
    const HeadingStream& heading = *log_.heading;
    visit_fixes(i, seg, heading.t_s, 0.0, next_heading, [&](std::size_t j, const MotionAt& at) {
      const double predicted = poses_[i][2] + at.motion.delta(2) + heading_bias_;
      const double measured = predicted + batch::wrapped(heading.heading_rad[j] - predicted);
      ++tally.headings;
      batch::FoldedIntervalResidual::add_heading(fold, at.motion, measured,
                                                 sensors_.heading_sigma_rad);
    });
  }
  if (!fold.empty()) folds_[i] = {origin, fold.factor(fold_columns_), &params_lin_};
}

bool BatchProblem::param_free(int p) const {
  if (p < 2) return true;
  if (p == 2) return batch_.estimate_track_width || track_prior_sigma_m() > 0.0;
  return tyre_in_fit(p - kTyreOffset) && !tyre_held(p - kTyreOffset);
}

batch::ColumnSelection<batch::kFoldedColumns> BatchProblem::fold_columns() const {
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

BatchProblem::OdometryInterval BatchProblem::odometry_interval(
    const PreintegratedSegment& segment) const {
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

double BatchProblem::white_gnss_sigma(std::size_t j) const {
  const double given = log_.gnss.sigma_m.empty() ? sensors_.gnss_sigma_m : log_.gnss.sigma_m[j];
  if (!gauss_markov()) return white_scale_ * given;
  const double gm2 = gm_sigma_m_ * gm_sigma_m_;
  const double drift = std::min(2.0 * batch_.keyframe_interval_s / (3.0 * gm_tau_s_), 1.0);
  return std::sqrt(square(white_gnss_sigma_unshared(given)) +
                   gnss_fixes_per_keyframe_ * gm2 * drift);
}

double BatchProblem::white_gnss_sigma_unshared(double given) const {
  if (!gauss_markov() || adapted_noise_) return white_scale_ * given;
  return std::sqrt(std::max(given * given - gm_sigma_m_ * gm_sigma_m_, 0.01 * given * given));
}

}  // namespace odocal::batch
