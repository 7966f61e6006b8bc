#include "odocal/estimation/driving_state.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace odocal {
namespace {

// A cumulative quantity sampled at increasing times (the stream's own, not copied: a long log's
// states are computed in a few values per sample); its value at any time by linear
// interpolation, clamped to the span.
struct Cumulative {
  const std::vector<double>& t_s;
  std::vector<double> value;

  double at(double t) const {
    if (t <= t_s.front()) return value.front();
    if (t >= t_s.back()) return value.back();
    const auto upper = std::upper_bound(t_s.begin(), t_s.end(), t);
    const std::size_t k = static_cast<std::size_t>(upper - t_s.begin());
    const double w = (t - t_s[k - 1]) / (t_s[k] - t_s[k - 1]);
    return (1.0 - w) * value[k - 1] + w * value[k];
  }
  // Mean rate over [t - h, t + h] clipped to the span.
  double rate(double t, double h) const {
    const double from = std::max(t - h, t_s.front()), to = std::min(t + h, t_s.back());
    return to > from ? (at(to) - at(from)) / (to - from) : 0.0;
  }
};

// Single precision for storage; clamped, since a float cannot hold what a corrupt log's
// increments over a vanishing time step could make of a speed.
float stored(double value) {
  constexpr double kLargest = 1e30;
  return static_cast<float>(std::clamp(value, -kLargest, kLargest));
}

// One IMU channel integrated on the IMU's time base (trapezoids); empty without samples.
Cumulative integrated(const ImuStream& imu, const std::vector<double>& channel) {
  Cumulative sum{imu.t_s, std::vector<double>(imu.size(), 0.0)};
  for (std::size_t k = 1; k < imu.size(); ++k) {
    sum.value[k] =
        sum.value[k - 1] + 0.5 * (channel[k] + channel[k - 1]) * (imu.t_s[k] - imu.t_s[k - 1]);
  }
  return sum;
}

// The states from the wheels' increments, each scaled by `factor(k, wheel)`.
template <class Factor>
std::vector<DrivingState> states_of(const WheelStream& wheels, const ImuStream* imu,
                                    const OdometryParams& params, double half_window_s,
                                    const Factor& factor) {
  std::vector<DrivingState> states(wheels.size());
  if (wheels.size() < 2) return states;
  Cumulative path{wheels.t_s, std::vector<double>(wheels.size(), 0.0)};
  Cumulative wheel_turn{wheels.t_s, std::vector<double>(wheels.size(), 0.0)};
  for (std::size_t k = 1; k < wheels.size(); ++k) {
    const WheelIncrement counted{wheels.rev_rl[k] * factor(k, RearWheel::kLeft),
                                 wheels.rev_rr[k] * factor(k, RearWheel::kRight)};
    const BodyIncrement step = body_increment(counted, params);
    path.value[k] = path.value[k - 1] + step.distance_m;
    wheel_turn.value[k] = wheel_turn.value[k - 1] + step.yaw_rad;
  }
  const bool gyro = imu != nullptr && imu->size() >= 2;
  static const ImuStream kNoImu;
  const ImuStream& measured = gyro ? *imu : kNoImu;
  const Cumulative gyro_path = integrated(measured, measured.wz_radps);
  const Cumulative forward = integrated(measured, measured.ax_mps2);
  const Cumulative left = integrated(measured, measured.ay_mps2);
  const double h = half_window_s;
  for (std::size_t k = 0; k < wheels.size(); ++k) {
    const double t = wheels.t_s[k];
    DrivingState& state = states[k];
    const double speed = path.rate(t, h);
    const bool imu_here = gyro && t >= imu->t_s.front() && t <= imu->t_s.back();
    const double yaw_rate = imu_here ? gyro_path.rate(t, h) : wheel_turn.rate(t, h);
    const double longitudinal = (path.rate(t + h, h) - path.rate(t - h, h)) / (2.0 * h);
    state.speed_mps = stored(speed);
    state.yaw_rate_radps = stored(yaw_rate);
    state.lateral_mps2 = stored(speed * yaw_rate);
    state.longitudinal_mps2 = stored(longitudinal);
    state.specific_force_x_mps2 = stored(imu_here ? forward.rate(t, h) : longitudinal);
    state.specific_force_y_mps2 = stored(imu_here ? left.rate(t, h) : speed * yaw_rate);
  }
  return states;
}

}  // namespace

std::vector<DrivingState> driving_states(const Log& log, const OdometryParams& params,
                                         double half_window_s) {
  return driving_states(log.wheels, log.imu ? &*log.imu : nullptr, params, half_window_s);
}

std::vector<DrivingState> driving_states(const WheelStream& wheels, const ImuStream* imu,
                                         const OdometryParams& params, double half_window_s) {
  return states_of(wheels, imu, params, half_window_s, [](std::size_t, RearWheel) { return 1.0; });
}

std::vector<DrivingState> driving_states(const WheelStream& wheels, const ImuStream* imu,
                                         const OdometryParams& params,
                                         const std::vector<DrivingState>& counted_at,
                                         const TyreModel& model, const VehicleBody& body,
                                         double half_window_s) {
  if (counted_at.size() != wheels.size())
    throw std::invalid_argument("driving_states: one driving state per wheel sample");
  if (model.plain()) return driving_states(wheels, imu, params, half_window_s);
  return states_of(wheels, imu, params, half_window_s, [&](std::size_t k, RearWheel wheel) {
    return tyre_factor(model, counted_at[k], wheel, body);
  });
}

WheelStream with_tyre_model(const WheelStream& wheels, const std::vector<DrivingState>& states,
                            const TyreModel& model, const VehicleBody& body) {
  if (states.size() != wheels.size())
    throw std::invalid_argument("with_tyre_model: one driving state per wheel sample");
  WheelStream corrected = wheels;
  if (model.plain()) return corrected;
  for (std::size_t k = 0; k < wheels.size(); ++k) {
    corrected.rev_rl[k] *= tyre_factor(model, states[k], RearWheel::kLeft, body);
    corrected.rev_rr[k] *= tyre_factor(model, states[k], RearWheel::kRight, body);
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
