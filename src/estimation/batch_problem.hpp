#pragma once
// The batch calibration's pose graph over a whole log (docs/batch-calibration.md): keyframe poses,
// the rear wheels' parameters and tyre coefficients, the sensors' offsets and the GNSS error
// states, with the Ceres problem that ties them to the log. Internal to the batch calibration.

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include "batch_folded_residuals.hpp"
#include "batch_residuals.hpp"
#include "batch_speed_residual.hpp"
#include "gnss_noise_estimate.hpp"
#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/estimation/model_adequacy.hpp"
#include "odocal/estimation/odometry_preintegration.hpp"
#include "odocal/model/tyre_car_prior.hpp"
#include "parallel_parts.hpp"

namespace odocal::batch {

// The index of the first of `times` (ascending) whose instant, time - lag_s, is at or after t_s
// (as visit_fixes compares it, so that parts of a pass meet where one pass would be).
inline std::size_t first_at_or_after(const std::vector<double>& times, double t_s,
                                     double lag_s = 0.0) {
  return static_cast<std::size_t>(
      std::partition_point(times.begin(), times.end(),
                           [&](double time) { return time - lag_s < t_s; }) -
      times.begin());
}

// Keyframe intervals per thread whose measurements for_each_measurement whitens before visiting
// them: a few MB at 100 Hz GNSS and heading.
inline constexpr std::size_t kMeasurementChunkPerThread = 512;

using Block2 = std::array<double, 2>;
using Block3 = std::array<double, 3>;
using ParamsBlock = std::array<double, kParams>;  // [c_RL, c_RR, t_R, tyre coefficients]
inline constexpr int kTyreOffset = 3;

// The batch problem: its unknowns live here across re-linearisations; each build() makes a fresh
// Ceres problem around the current pre-integration (batch_problem.cpp builds and solves it,
// batch_problem_preintegration.cpp pre-integrates the wheels and folds the fixes,
// batch_considered_uncertainty.cpp moves what the log takes as known).
class BatchProblem {
 public:
  // `wheels`: the wheel stream it fits, log.wheels as it is or with its heading smoothed
  // (CalibrationRun::batch_wheels); it and every other stream are the log's.
  BatchProblem(const Log& log, FittedWheels wheels, const ReferenceTrajectory& reference,
               const BatchOptions& options, const CalibrationOptions& common,
               const OdometryParams& nominal);
  // The folds and the problem point into the object's own members: it stays where it was built.
  BatchProblem(const BatchProblem&) = delete;
  BatchProblem& operator=(const BatchProblem&) = delete;

  bool gauss_markov() const { return gm_sigma_m_ > 0.0; }

  // Fits the tyre model's terms of one family from here on (none: the plain model), every
  // coefficient back at zero.
  void set_tyre_terms(std::optional<TyreTerms> terms);
  bool tyre_fitted() const { return tyre_terms_.has_value(); }
  std::optional<TyreTerms> tyre_terms() const { return tyre_terms_; }
  // Whether coefficient j belongs to the family being fitted (held at zero or free).
  bool tyre_in_fit(int j) const {
    return tyre_terms_ && kTyreCoefficients[static_cast<std::size_t>(j)].terms == *tyre_terms_;
  }
  // Holds coefficient j at zero from the next solve on (hold_at_car_values may move it after the
  // decisions): the log cannot identify it. Its sigma when it was free is kept for the report,
  // and with its value there for where it is held and its share of the circumferences' sigma; a
  // fit that wandered says nothing of the value; one below zero (a slip, tyre_nonnegative) is
  // held for its sign, not for its spread.
  enum class FreeValue { kEstimate, kWandered, kBelowZero };
  void hold_tyre_coefficient(int j, double sigma, FreeValue value = FreeValue::kEstimate);
  // Moves every held physical coefficient from zero to where a car's value of it and what the
  // log said while it was free put it together (tyre_car_prior.hpp), for the next solve on;
  // whether any moved. Not where the fit wandered: a log whose fit does not settle is no car's
  // tyre (the Husky robot).
  bool hold_at_car_values();
  CarCoefficient car_coefficient(int j) const {
    return car_tyre_coefficient(j, body_,
                                0.5 * (nominal_.circumference_rl_m + nominal_.circumference_rr_m));
  }
  // Whether coefficient j cannot be below zero: a slip of an axle the body drives or brakes (a
  // free-rolling axle's is the model's slop, either way; tyre_car_prior.hpp).
  bool tyre_nonnegative(int j) const {
    return (j == kDriveSlipCoefficient || j == kBrakeSlipCoefficient) &&
           car_coefficient(j).mean > 0.0;
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
  Unknowns unknowns(Folds folds = Folds::kRebuild) const;
  void set_unknowns(const Unknowns& u);

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
  void restart();
  bool tyre_held(int j) const { return tyre_held_sigma_[static_cast<std::size_t>(j)] > 0.0; }
  double tyre_held_sigma(int j) const { return tyre_held_sigma_[static_cast<std::size_t>(j)]; }
  double tyre_held_estimate(int j) const {
    return tyre_held_estimate_[static_cast<std::size_t>(j)];
  }
  bool tyre_held_below_zero(int j) const {
    return tyre_held_below_zero_[static_cast<std::size_t>(j)];
  }
  int free_tyre_coefficients() const;
  // Whether the free fit wandered, so that its coefficients were held at zero (solve_tyre_model).
  bool tyre_fit_wandered() const;
  TyreModel tyre_model() const {
    return TyreModel::from(Eigen::Map<const TyreModel::Vector>(params_.data() + kTyreOffset));
  }
  const TyreModel::Vector& regressor_rms() const { return regressor_rms_; }
  // The Bayesian information criterion of the last solve: its cost (robust where the loss is)
  // as -log-likelihood, and the unknowns that the model choice adds.
  double information_criterion(const ceres::Solver::Summary& solver) const;

  // The GNSS noise model from here on: every fix's white sigma scaled by `white_scale`, and a
  // Gauss-Markov error (0: none).
  void set_gnss_noise(double white_scale, double gm_sigma_m, double gm_tau_s);
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

  // RMS of the white sigma the fixes were given (gnss.csv's sigma_m, else the configured one),
  // whatever noise they are solved under now.
  double configured_gnss_sigma_rms_m() const {
    return rms_over_given_sigmas([](double given) { return given; });
  }

  // Every fix in the problem: measured minus fitted position (metres), robust loss not applied;
  // a modelled Gauss-Markov error counts as part of it.
  // (Computed again at each call, segment by segment: a long log's errors are not held.)
  GnssResidualSource gnss_errors() const;
  // The fixes' and heading samples' mean errors at the current unknowns
  // (batch_mounting_residuals.cpp).
  MountingResiduals mounting_residuals() const;

  // Every odometry interval in the problem: fitted poses, and their relative motion minus the
  // wheels' at the fitted parameters (model_adequacy.hpp). Where the gyro is used, the heading
  // residual is its turn (less the fitted bias) minus the wheels': the poses' own turn is
  // partly the wheels', which would hide what the wheels get wrong.
  std::vector<OdometryResidualSample> odometry_errors() const;

  // Integrates the odometry of every segment at the current parameters. `slip_floor` loosens the
  // slip noise for a first, coarse solve: started from the layer-1 reference, a nearly rigid
  // odometry chain would take the solver many small steps.
  // `remeasure_states`: false for a round that only re-weights (the driving state stays as the
  // last re-linearisation measured it).
  // Folds::kKeep keeps the folds of GNSS fixes and heading samples of the last pre-integration
  // (they must be at the same unknowns): only the odometry and the Doppler speed, the residuals
  // that the body's numbers reach at the scale of the whole log, are pre-integrated again.
  void preintegrate_all(double slip_floor = 0.0, bool remeasure_states = true,
                        Folds folds = Folds::kRebuild);

  // The problem at the current unknowns, built and not solved (as solve() builds it).
  void build();

  // max_iterations: 0 for the configured limit.
  ceres::Solver::Summary solve(int max_iterations = 0);

  // Largest relative change of the parameters since the last pre-integration (for the tyre
  // coefficients: of the circumference they make at the log's RMS driving state; for the latency,
  // a millisecond counts as 1e-4: the fixes' instants and the Doppler speed's window are shifted
  // by the latency they were built at, and the rest is taken to first order).
  double relative_change() const {
    constexpr double kPerSecondOfLatency = 0.1;
    return std::max(change_from(params_lin_),
                    kPerSecondOfLatency * std::abs(latency_ - latency_lin_));
  }

  // The same measure of the parameters' change since `earlier`.
  double change_from(const Eigen::Ref<const batch::ParamsVector>& earlier) const;

  // 1-sigma covariance blocks of the global unknowns; none when the information is singular
  // (some unknowns cannot be told apart: batch_covariance.hpp).
  struct Uncertainty {
    Eigen::Matrix<double, batch::kParams, batch::kParams> params =
        Eigen::Matrix<double, batch::kParams, batch::kParams>::Zero();
    Eigen::Matrix2d lever = Eigen::Matrix2d::Zero();
    double gyro_bias{}, heading_bias{}, latency{};
  };
  std::optional<Uncertainty> uncertainty();

  const ParamsBlock& params() const { return params_; }

  // How far the estimate moves with what the log cannot identify and the fit takes as known:
  // per number, one Gauss-Newton step from the solution with it moved by a quarter of its
  // uncertainty, scaled to the whole (the linear sensitivity, without solving again); the outer
  // products summed, as for independent errors. The numbers:
  // - the body's (the physical terms' geometry, docs/tyre-model.md). The GNSS and heading folds
  //   are built once, at the solution: the body reaches them only through the wheels' motion
  //   within one keyframe interval, while it moves the odometry and the Doppler speed over the
  //   whole log;
  // - the track width, where the plain model holds it, by track_width_uncertainty (the tyre
  //   models carry the load that moves the track the wheels roll on);
  // - the tyre coefficients held, by their spread about where they are held (a car's value, and
  //   what the log said while they were free; a regression term, at zero, by what the log said
  //   alone: held_coefficient_sigma). Holding one makes an
  //   error of the car's own value less the held one, which the free ones and the circumferences
  //   take up (the urban drive, seed 8: the brake slip held at zero, c_RL +10 mm at a sigma of
  //   2.5 mm without it). The coefficient
  //   is linear in the pre-integration's Jacobian, which carries the step; the folds keep theirs,
  //   as for the body.
  // The solution and its problem are restored after.
  void add_considered_uncertainty();
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
  // What the accelerometer's forward offset left in imu.csv's ax is uncertain by, m/s^2
  // (accelerometer_offset.hpp; 0: the log has no accelerometer). The physical terms take ax for
  // the drive force, so add_considered_uncertainty moves it by a step of this too.
  void set_forward_offset_sigma(double sigma_mps2) { forward_offset_sigma_mps2_ = sigma_mps2; }
  double forward_offset_sigma() const { return forward_offset_sigma_mps2_; }
  // Of the parameters, from that offset; and what its step moved them by (none where nothing).
  const Eigen::Matrix<double, batch::kParams, batch::kParams>& forward_offset_covariance() const {
    return forward_offset_covariance_;
  }
  const std::optional<Response>& forward_offset_response() const {
    return forward_offset_response_;
  }
  // Of the parameters, from the held track's uncertainty (track_width_uncertainty), for the
  // plain model (zero where the track is estimated or exact, or a tyre model is fitted).
  const Eigen::Matrix<double, batch::kParams, batch::kParams>& track_covariance() const {
    return track_covariance_;
  }
  // Fits the plain model's track width under a prior of track_width_uncertainty about
  // vehicle.yaml's, in place of the held track's share (docs/batch-calibration.md, "The track
  // under its prior"). Off by default: the share is what covers load transfer.
  void set_track_prior(bool on) { track_prior_ = on; }
  // That prior's sigma, metres; 0 where it is off, the track is estimated outright, a tyre model
  // is fitted or the track is taken as exact.
  double track_prior_sigma_m() const;
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
    return wheels_.t_s[keyframes_.back()] - wheels_.t_s[keyframes_.front()];
  }
  std::size_t gnss_residuals() const { return gnss_residuals_; }
  // The Doppler residuals' noise from the next pre-integration on: the configured one times this.
  void set_speed_noise(double scale) { speed_scale_ = scale; }
  double speed_noise_scale() const { return speed_scale_; }
  // Every Doppler residual at the current unknowns, whitened (robust loss not applied).
  std::vector<double> speed_whitened() const;
  // Keyframe interval i's Doppler residual (it must have one), whitened: (wheels - Doppler) /
  // sigma.
  double speed_whitened(std::size_t i) const;
  // Keyframe intervals whose Doppler speed is in the fit.
  std::size_t speed_intervals() const {
    return static_cast<std::size_t>(
        std::count_if(speed_.begin(), speed_.end(), [](const auto& r) { return r.has_value(); }));
  }
  // Keyframe intervals with odometry in the fit (not a gap, inside the gentle limits), of all.
  std::pair<std::size_t, std::size_t> gentle_intervals() const;

 private:
  bool use_speed() const { return doppler_sigma_mps_ > 0.0; }

  // Segment i's Doppler speed against its wheels (none where the fixes do not cover it or a wheel
  // turns backwards: the Doppler speed has no sign).
  std::optional<batch::SpeedResidual> speed_residual(std::size_t i, const PreintegratedSegment& seg,
                                                     const OdometryParams& at) const;

  void add_speed();

  // The pre-integrated motion of segment i from its keyframe to time t_s (inside the segment),
  // with the reference point's velocity there (keyframe frame).
  struct MotionAt {
    batch::RelativeMotion motion;
    Eigen::Vector2d velocity;
  };
  // The segment's sample s whose increment to s + 1 spans t_s (inside the segment).
  std::size_t segment_sample(const PreintegratedSegment& seg, double t_s) const;

  MotionAt motion_at(std::size_t i, const PreintegratedSegment& seg, double t_s) const;

  // Calls visit(k, motion) for every sample k of a stream's times `t_s` (GNSS fixes, heading
  // samples) whose instant, t_s - lag_s, lies inside segment i, from `next` on (samples before the
  // segment are skipped; `next` ends past it). The motion is that instant's, its position moved
  // on by the velocity there times lag_s: a residual that subtracts velocity x latency then puts
  // a fix stamped t at t - lag_s exactly and takes only latency - lag_s to first order.
  template <typename Visit>
  void visit_fixes(std::size_t i, const PreintegratedSegment& seg, const std::vector<double>& t_s,
                   double lag_s, std::size_t& next, Visit&& visit) const {
    const double begin = wheels_.t_s[keyframes_[i]], end = wheels_.t_s[keyframes_[i + 1]];
    while (next < t_s.size() && t_s[next] - lag_s < begin) ++next;
    for (; next < t_s.size() && t_s[next] - lag_s < end; ++next) {
      MotionAt at = motion_at(i, seg, t_s[next] - lag_s);
      at.motion.delta.head<2>() += lag_s * at.velocity;
      visit(next, at);
    }
  }

  // Fix j's whitened residual at the current unknowns (robust loss not applied).
  Eigen::Vector2d whitened_fix(std::size_t j, std::size_t i, const MotionAt& at) const;

  // rho(s), rho'(s) of the GNSS loss at a squared whitened residual s.
  std::array<double, 3> robust(double s) const {
    std::array<double, 3> rho{s, 1.0, 0.0};
    if (loss_) loss_->Evaluate(s, rho.data());
    return rho;
  }

  bool use_heading() const { return batch_.use_heading && log_.heading; }
  // How long before its stamp a GNSS fix is placed (visit_fixes): the latency the problem was
  // linearised at.
  double fix_lag_s() const { return latency_lin_; }
  // Where a pass over the intervals in time order stands at interval i's start, so that a part of
  // them can start there: its first GNSS fix and heading sample (0 without headings).
  struct MeasurementCursors {
    std::size_t fix, heading;
  };
  MeasurementCursors cursors_at(std::size_t interval) const {
    const double start_s = wheels_.t_s[keyframes_[interval]];
    return {first_at_or_after(log_.gnss.t_s, start_s, fix_lag_s()),
            use_heading() ? first_at_or_after(log_.heading->t_s, start_s) : 0};
  }

  // What the folds of one part of the intervals counted (preintegrate_all folds the parts on
  // threads and adds their tallies up).
  struct FoldTally {
    std::size_t fixes = 0, headings = 0;
    float max_weight_change = 0.0f;
  };
  // The fixes of segment i, each weighted by the robust loss at the current unknowns, and its
  // heading samples folded into one residual.
  void fold_interval(std::size_t i, const PreintegratedSegment& seg, std::size_t& next_fix,
                     std::size_t& next_heading, FoldTally& tally);

  // Calls visit_fix(fix, segment, whitened residual) for every fix in the problem and
  // visit_heading(segment, whitened residual) for every heading sample, in time order, at the
  // current unknowns and as the folds linearise them, pre-integrating again segment by segment. The
  // segments of a chunk are whitened on threads (parallel_parts.hpp) and visited in order after
  // them, so that memory stays per chunk and the visits are the same on any number of threads.
  // With `interval_stride` n > 1, only every n-th interval's.
  template <typename VisitFix, typename VisitHeading>
  void for_each_measurement(VisitFix&& visit_fix, VisitHeading&& visit_heading,
                            std::size_t interval_stride = 1) const {
    const OdometryParams at{params_lin_(0), params_lin_(1), params_lin_(2)};
    const TyreConditions tyre{states_,
                              TyreModel::from(params_lin_.tail<TyreModel::kCoefficients>()), body_};
    constexpr bool kHeadings = !std::is_same_v<std::decay_t<VisitHeading>, std::nullptr_t>;
    const bool headings = kHeadings && use_heading();
    struct Whitened {
      std::size_t fix, segment;  // a heading sample: its segment only
      Eigen::Vector2d value;     // a heading sample's in x
      bool heading;
    };
    const std::size_t intervals = keyframes_.size() > 1 ? keyframes_.size() - 1 : 0;
    const int threads = usable_threads(batch_.threads);
    const std::size_t chunk = kMeasurementChunkPerThread * static_cast<std::size_t>(threads);
    std::vector<std::vector<Whitened>> whitened(static_cast<std::size_t>(threads));
    const auto whiten = [&](std::size_t part, std::size_t begin, std::size_t end) {
      std::vector<Whitened>& out = whitened[part];
      out.clear();
      if (begin == end) return;
      auto [next_fix, next_heading] = cursors_at(begin);
      for (std::size_t i = begin; i < end; ++i) {
        if (i % interval_stride != 0 || gap_segment(i)) continue;
        const PreintegratedSegment seg = preintegrate(wheels_, keyframes_[i], keyframes_[i + 1], at,
                                                      noise_, tyre_fitted() ? &tyre : nullptr);
        visit_fixes(i, seg, log_.gnss.t_s, fix_lag_s(), next_fix,
                    [&](std::size_t j, const MotionAt& motion) {
                      out.push_back({j, i, whitened_fix(j, i, motion), false});
                    });
        if (!headings) continue;
        visit_fixes(i, seg, log_.heading->t_s, 0.0, next_heading,
                    [&](std::size_t j, const MotionAt& motion) {
                      const batch::HeadingResidual residual{
                          motion.motion, log_.heading->heading_rad[j], sensors_.heading_sigma_rad};
                      double value = 0.0;
                      residual(poses_[i].data(), params_.data(), &heading_bias_,
                               count_error_[i].data(), &value);
                      out.push_back({j, i, Eigen::Vector2d(value, 0.0), true});
                    });
      }
    };
    for (std::size_t from = 0; from < intervals; from += chunk) {
      const std::size_t to = std::min(intervals, from + chunk);
      const std::size_t parts =
          run_in_parts(to - from, threads, [&](std::size_t part, std::size_t b, std::size_t e) {
            whiten(part, from + b, from + e);
          });
      for (std::size_t part = 0; part < parts; ++part) {
        for (const Whitened& w : whitened[part]) {
          if constexpr (kHeadings) {
            if (w.heading) {
              visit_heading(w.segment, w.value.x());
              continue;
            }
          }
          visit_fix(w.fix, w.segment, w.value);
        }
      }
    }
  }
  template <typename Visit>
  void for_each_fix(Visit&& visit) const {
    for_each_measurement(std::forward<Visit>(visit), nullptr);
  }

  // The log's IMU stream; null without imu.csv.
  const ImuStream* imu() const { return log_.imu ? &*log_.imu : nullptr; }
  // A segment that is a wheel gap: no odometry links its keyframes (GNSS and the gyro do).
  bool gap_segment(std::size_t i) const { return wheels_.breaks_at(keyframes_[i + 1]); }

  // Whether parameter p is estimated in this solve (the rest are held where they are).
  bool param_free(int p) const;

  // The entries of a fold's phi (batch_folded_residuals.hpp) that this solve can move.
  batch::ColumnSelection<batch::kFoldedColumns> fold_columns() const;

  bool gentle_limits() const {
    return batch_.gentle_max_speed_mps > 0.0 || batch_.gentle_max_longitudinal_mps2 > 0.0 ||
           batch_.gentle_max_lateral_mps2 > 0.0;
  }
  // An interval whose driving exceeds a gentle limit: no odometry residual, and the fixes inside
  // it use the wheels only to interpolate from the keyframe (no parameter derivative).
  void mark_gentle_segments();

  // Per keyframe interval, the odometry residual of its pre-integration (the per-sample motion
  // lives only while its fixes are folded). The problem's blocks point to these rather than own
  // copies, so that a long log keeps one: they are replaced only after the problem is freed.
  struct OdometryInterval {
    batch::OdometryResidual residual;
    Eigen::Matrix3d sqrt_covariance;  // lower Cholesky factor: error = it x whitened
  };
  OdometryInterval odometry_interval(const PreintegratedSegment& segment) const;

  void add_odometry();

  // Without a quantisation (exact wheel angles or speeds) the count errors stay zero.
  void add_count_priors();

  // The sigma of fix j's residual. A configured Gauss-Markov error is taken out of the
  // configured total; an adapted model's white part was estimated as such. The Gauss-Markov
  // error is held per keyframe, but it drifts within one (by sigma^2 2 dt / (3 tau) on average
  // over the keyframe, for dt << tau), and that drift is shared by the keyframe's n fixes: each
  // fix carries n times its variance, so that the keyframe as a whole is weighted right.
  double white_gnss_sigma(std::size_t j) const;
  // The white part of a fix given `given`, without the keyframe's share of the drift.
  double white_gnss_sigma_unshared(double given) const;
  static double square(double v) { return v * v; }
  // RMS over the fixes of sigma(the sigma each was given: gnss.csv's, else the configured one).
  template <typename Sigma>
  double rms_over_given_sigmas(const Sigma& sigma) const {
    if (log_.gnss.sigma_m.empty()) return sigma(sensors_.gnss_sigma_m);
    double sum = 0.0;
    for (const double given : log_.gnss.sigma_m) sum += square(sigma(given));
    return std::sqrt(sum / static_cast<double>(log_.gnss.sigma_m.size()));
  }

  ceres::LossFunction* gnss_loss() const;

  void add_folds();

  // The gyro's turn over each keyframe interval the IMU covers (the trapezoid of its samples).
  void add_gyro();
  // After a solve: each pose's yaw within half a turn of its predecessor's plus the interval's
  // measured turn (the wheels', else the gyro's). The residuals measure turns modulo 2 pi, so a
  // solution may leave two poses a whole turn apart where the reference that started them swept
  // one; whatever reads a turn from two poses (model adequacy, mounting) takes them continuous.
  void make_yaws_continuous();

  void add_gauss_markov();

  void hold_unrequested();

  const Log& log_;
  const FittedWheels wheels_;
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
  double latency_lin_ = 0.0;  // the latency the fixes' and Doppler speed's residuals were built at
  std::vector<DrivingState> states_;  // per wheel sample; empty without tyre model and limits
  std::vector<std::uint8_t> rough_segment_;  // per interval: outside the gentle limits
  TyreModel::Vector regressor_rms_ = TyreModel::Vector::Zero();
  bool track_prior_ = false;
  std::optional<TyreTerms> tyre_terms_;  // the family of tyre coefficients fitted (none: plain)
  // Of the parameters, from the body's uncertainty and the held coefficients' spread
  // (add_considered_uncertainty).
  Eigen::Matrix<double, batch::kParams, batch::kParams> body_covariance_ =
      Eigen::Matrix<double, batch::kParams, batch::kParams>::Zero();
  Eigen::Matrix<double, batch::kParams, batch::kParams> held_covariance_ =
      Eigen::Matrix<double, batch::kParams, batch::kParams>::Zero();
  std::vector<Response> body_responses_;
  std::vector<HeldResponse> held_responses_;
  double forward_offset_sigma_mps2_{};
  Eigen::Matrix<double, batch::kParams, batch::kParams> forward_offset_covariance_ =
      Eigen::Matrix<double, batch::kParams, batch::kParams>::Zero();
  std::optional<Response> forward_offset_response_;
  Eigen::Matrix<double, batch::kParams, batch::kParams> track_covariance_ =
      Eigen::Matrix<double, batch::kParams, batch::kParams>::Zero();
  std::array<double, 2> model_spread_m_{};
  std::array<double, TyreModel::kCoefficients> tyre_held_sigma_{};     // > 0: held
  std::array<double, TyreModel::kCoefficients> tyre_held_estimate_{};  // its value while free
  std::array<double, TyreModel::kCoefficients> tyre_held_value_{};     // where it is held
  std::array<bool, TyreModel::kCoefficients> tyre_held_wandered_{};    // its free fit wandered
  std::array<bool, TyreModel::kCoefficients> tyre_held_below_zero_{};  // held for its sign
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

}  // namespace odocal::batch
