#include "odocal/estimation/driving_state.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "odocal/estimation/road_grade.hpp"
#include "parallel_parts.hpp"

namespace odocal {
namespace {

// A cumulative quantity sampled at increasing times (the stream's own, not copied: a long log's
// states are computed in a few values per sample); its value at any time by linear
// interpolation, clamped to the span.
struct Cumulative {
  const std::vector<double>& t_s;
  std::vector<double> value;

  // `k` is where the last lookup of the same sequence of times ended: the states ask at times that
  // rise with the sample, so it walks a step or two where a search over a 10-hour drive would take
  // twenty. It ends at the first sample later than t, as std::upper_bound would.
  double at(double t, std::size_t& k) const {
    if (t <= t_s.front()) return value.front();
    if (t >= t_s.back()) return value.back();
    k = std::clamp<std::size_t>(k, 1, t_s.size() - 1);
    while (t_s[k] <= t) ++k;
    while (t_s[k - 1] > t) --k;
    const double w = (t - t_s[k - 1]) / (t_s[k] - t_s[k - 1]);
    return (1.0 - w) * value[k - 1] + w * value[k];
  }
  // Mean rate over [t - h, t + h] clipped to the span; `from_k` and `to_k` as for at().
  double rate(double t, double h, std::size_t& from_k, std::size_t& to_k) const {
    const double from = std::max(t - h, t_s.front()), to = std::min(t + h, t_s.back());
    return to > from ? (at(to, to_k) - at(from, from_k)) / (to - from) : 0.0;
  }
};

// Single precision for storage; clamped, since a float cannot hold what a corrupt log's
// increments over a vanishing time step could make of a speed.
float stored(double value) {
  constexpr double kLargest = 1e30;
  return static_cast<float>(std::clamp(value, -kLargest, kLargest));
}

// One IMU channel's integral (trapezoids) at non-decreasing times, without storing it (a long
// drive's IMU would take 8 bytes per sample and channel): the same values, in the same order of
// additions, as a stored cumulative interpolated linearly and clamped to the span.
class RunningIntegral {
 public:
  RunningIntegral(const std::vector<double>& t_s, const std::vector<double>& channel)
      : t_s_(t_s), channel_(channel) {}
  double at(double t) {
    while (k_ + 1 < t_s_.size() && t_s_[k_ + 1] <= t) {
      sum_ += segment(k_);
      ++k_;
    }
    if (t <= t_s_[k_] || k_ + 1 == t_s_.size()) return sum_;
    const double w = (t - t_s_[k_]) / (t_s_[k_ + 1] - t_s_[k_]);
    return (1.0 - w) * sum_ + w * (sum_ + segment(k_));
  }

 private:
  double segment(std::size_t k) const {
    return 0.5 * (channel_[k + 1] + channel_[k]) * (t_s_[k + 1] - t_s_[k]);
  }
  const std::vector<double>& t_s_;
  const std::vector<double>& channel_;
  std::size_t k_ = 0;
  double sum_ = 0.0;
};

// The mean of one IMU channel over [t - h, t + h] clipped to its span, at non-decreasing t.
class RunningMean {
 public:
  RunningMean(const ImuStream& imu, const std::vector<double>& channel)
      : t_s_(imu.t_s), from_(imu.t_s, channel), to_(imu.t_s, channel) {}
  double at(double t, double h) {
    const double from = std::max(t - h, t_s_.front()), to = std::min(t + h, t_s_.back());
    const double begin = from_.at(from), end = to_.at(to);
    return to > from ? (end - begin) / (to - from) : 0.0;
  }

 private:
  const std::vector<double>& t_s_;
  RunningIntegral from_, to_;
};

// Fills `states` (one per wheel sample) from the wheels' increments, each scaled by its wheel's
// entry of `factors(k)` ({left, right}; both at once, since they share the axle's forces), which
// may read `states` as they were: every factor is taken before any state is written (the batch
// measures the state again in place). Both passes run in parts on
// `threads` (parallel_parts.hpp) with the same arithmetic in the same order as on one: the
// running sums are added up on the caller, and each part's running means start from the
// stream's beginning.
template <class Factors>
void fill_states(const FittedWheels& wheels, const ImuStream* imu, const OdometryParams& params,
                 double half_window_s, const Factors& factors, std::vector<DrivingState>& states,
                 int threads) {
  states.resize(wheels.size());
  if (wheels.size() < 2) {
    std::fill(states.begin(), states.end(), DrivingState{});
    return;
  }
  // Each sample's own step first (the factors are the costly part), then their running sums.
  Cumulative path{wheels.t_s, std::vector<double>(wheels.size(), 0.0)};
  Cumulative wheel_turn{wheels.t_s, std::vector<double>(wheels.size(), 0.0)};
  batch::run_in_parts(wheels.size() - 1, threads, [&](std::size_t, std::size_t b, std::size_t e) {
    for (std::size_t k = b + 1; k <= e; ++k) {
      const WheelIncrement n = wheels.increment(k);
      const std::array<double, 2> factor = factors(k);
      const WheelIncrement counted{n.rev_rl * factor[0], n.rev_rr * factor[1]};
      const BodyIncrement step = body_increment(counted, params);
      path.value[k] = step.distance_m;
      wheel_turn.value[k] = step.yaw_rad;
    }
  });
  for (std::size_t k = 1; k < wheels.size(); ++k) {
    path.value[k] = path.value[k - 1] + path.value[k];
    wheel_turn.value[k] = wheel_turn.value[k - 1] + wheel_turn.value[k];
  }
  const bool measured = imu != nullptr && imu->size() >= 2;
  static const ImuStream kNoImu{{0.0, 1.0}, {0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}};
  const ImuStream& source = measured ? *imu : kNoImu;
  const double h = half_window_s, h_yaw = std::min(h, kYawAccelerationHalfWindowS);
  const std::vector<double>& forces = wheels.drive_force_n;
  const auto fill_part = [&](std::size_t, std::size_t begin, std::size_t end) {
    RunningMean gyro(source, source.wz_radps), forward(source, source.ax_mps2),
        left(source, source.ay_mps2), gyro_behind(source, source.wz_radps),
        gyro_ahead(source, source.wz_radps);
    // Where each sequence of lookup times (t - 2h .. t + 2h) has got to.
    std::size_t at_minus_2h = begin, at_minus_h = begin, at_t = begin, at_plus_h = begin,
                at_plus_2h = begin, turn_from = begin, turn_to = begin, turn_minus_2h = begin,
                turn_t = begin, turn_plus_2h = begin;
    for (std::size_t k = begin; k < end; ++k) {
      const double t = wheels.t_s[k];
      DrivingState& state = states[k];
      const double speed = path.rate(t, h, at_minus_h, at_plus_h);
      const bool imu_here = measured && t >= imu->t_s.front() && t <= imu->t_s.back();
      const double yaw_rate = imu_here ? gyro.at(t, h) : wheel_turn.rate(t, h, turn_from, turn_to);
      const double longitudinal =
          (path.rate(t + h, h, at_t, at_plus_2h) - path.rate(t - h, h, at_minus_2h, at_t)) /
          (2.0 * h);
      state.speed_mps = stored(speed);
      state.yaw_rate_radps = stored(yaw_rate);
      state.longitudinal_mps2 = stored(longitudinal);
      // As the wheels' acceleration: the difference of the means over the half windows either side.
      // The gyro's over a shorter spacing, min(h, kYawAccelerationHalfWindowS).
      const double yaw_acceleration =
          imu_here
              ? (gyro_ahead.at(t + h_yaw, h_yaw) - gyro_behind.at(t - h_yaw, h_yaw)) / (2.0 * h_yaw)
              : (wheel_turn.rate(t + h, h, turn_t, turn_plus_2h) -
                 wheel_turn.rate(t - h, h, turn_minus_2h, turn_t)) /
                    (2.0 * h);
      state.yaw_acceleration_radps2 = stored(yaw_acceleration);
      // The specific force the tyres push with: on a hill, with the slope's gravity that the
      // projection took out of the accelerometer (a wheel climbing slips as one accelerating
      // does). Where the grade is not known the projection left the increments alone: level, as
      // without.
      const bool graded = !wheels.grade.empty() && std::isfinite(wheels.grade[k]);
      const double slope = graded ? slope_gravity_mps2(wheels.grade[k]) : 0.0;
      // The accelerometer over this sample's own increment, not over +-h: the physical terms
      // are products and quotients of force and load with a split at zero force, so a state
      // averaged over half a second puts the braking into the turn that follows it, and dead
      // reckoning sums what that does to the wheels' difference (docs/tyre-model.md, "The slip
      // curve and the state of one sample").
      const double from = wheels.t_s[k > 0 ? k - 1 : 0], to = wheels.t_s[k > 0 ? k : 1];
      const double mid = 0.5 * (from + to), half = 0.5 * (to - from);
      state.specific_force_x_mps2 =
          stored((imu_here ? forward.at(mid, half) : longitudinal) + slope);
      state.specific_force_y_mps2 = stored(imu_here ? left.at(mid, half) : speed * yaw_rate);
      // The log's force over the same increment (trapezoid of its two rows); a row not known
      // (NaN, a block without the column) leaves the accelerometer's.
      if (!forces.empty())
        state.drive_force_n = stored(k > 0 ? 0.5 * (forces[k - 1] + forces[k]) : forces[0]);
    }
  };
  batch::run_in_parts(wheels.size(), threads, fill_part);
}

}  // namespace

std::vector<DrivingState> driving_states(const Log& log, const OdometryParams& params,
                                         double half_window_s) {
  return driving_states(log.wheels, log.imu ? &*log.imu : nullptr, params, half_window_s);
}

std::vector<DrivingState> driving_states(const FittedWheels& wheels, const ImuStream* imu,
                                         const OdometryParams& params, double half_window_s) {
  std::vector<DrivingState> states;
  fill_states(
      wheels, imu, params, half_window_s,
      [](std::size_t) {
        return std::array{1.0, 1.0};
      },
      states, 1);
  return states;
}

std::vector<DrivingState> driving_states(const FittedWheels& wheels, const ImuStream* imu,
                                         const OdometryParams& params,
                                         const std::vector<DrivingState>& counted_at,
                                         const TyreModel& model, const VehicleBody& body,
                                         double half_window_s) {
  std::vector<DrivingState> states = counted_at;
  measure_driving_states_again(wheels, imu, params, model, body, states, half_window_s);
  return states;
}

void measure_driving_states_again(const FittedWheels& wheels, const ImuStream* imu,
                                  const OdometryParams& params, const TyreModel& model,
                                  const VehicleBody& body, std::vector<DrivingState>& states,
                                  double half_window_s, int threads) {
  if (states.size() != wheels.size())
    throw std::invalid_argument("driving_states: one driving state per wheel sample");
  fill_states(
      wheels, imu, params, half_window_s,
      [&](std::size_t sample) {
        const RearTyreFactors both = rear_tyre_factors_with_gradient(model, states[sample], body);
        return std::array{both.left.value, both.right.value};
      },
      states, batch::usable_threads(threads));
}

WheelStream with_tyre_model(const WheelStream& wheels, const std::vector<DrivingState>& states,
                            const TyreModel& model, const VehicleBody& body) {
  if (states.size() != wheels.size())
    throw std::invalid_argument("with_tyre_model: one driving state per wheel sample");
  WheelStream corrected = wheels;
  if (model.plain()) return corrected;
  const bool side_slips = model.k_side_slip_s2pm != 0.0;
  if (side_slips) corrected.side_slip_rad.resize(wheels.size());
  for (std::size_t k = 0; k < wheels.size(); ++k) {
    const RearTyreFactors factors = rear_tyre_factors_with_gradient(model, states[k], body);
    corrected.rev_rl[k] *= factors.left.value;
    corrected.rev_rr[k] *= factors.right.value;
    if (side_slips)
      corrected.side_slip_rad[k] = static_cast<float>(side_slip_rad(model, states[k], body));
  }
  return corrected;
}

WheelStream with_tyre_model(const Log& log, const OdometryParams& params, const TyreModel& model) {
  if (model.plain()) return log.wheels;
  // Once more with the state the corrected wheels show, as the batch measures it.
  const ImuStream* imu = log.imu ? &*log.imu : nullptr;
  const VehicleBody body = log.vehicle.body_geometry();
  const std::vector<DrivingState> counted =
      driving_states(log.wheels, imu, params, driving_states(log, params), model, body);
  return with_tyre_model(log.wheels, counted, model, body);
}

}  // namespace odocal
