#include "odocal/estimation/accelerometer_walk.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "odocal/estimation/median.hpp"

namespace odocal {
namespace {

// The heading increment of wheel sample k with the model applied at `state`.
double heading_step(const WheelStream& wheels, std::size_t k, const DrivingState& state,
                    const TyreModel& model, const VehicleBody& body, const OdometryParams& params) {
  const RearTyreFactors factors = rear_tyre_factors_with_gradient(model, state, body);
  const WheelIncrement counted{wheels.rev_rl[k] * factors.left.value,
                               wheels.rev_rr[k] * factors.right.value};
  return body_increment(counted, params).yaw_rad;
}

// d(heading step) / d(specific force) by central differences: the slip curve's bend and the
// split at zero force make the terms nonlinear, and a sample's noise is small against both.
struct Sensitivity {
  double forward, left;
};
Sensitivity heading_sensitivity(const WheelStream& wheels, std::size_t k, DrivingState state,
                                const TyreModel& model, const VehicleBody& body,
                                const OdometryParams& params) {
  constexpr float kStep = 0.01f;  // m/s^2, a twentieth of a phone's noise
  const auto slope = [&](float DrivingState::*force) {
    const float at = state.*force, above = at + kStep, below = at - kStep;
    state.*force = above;
    const double up = heading_step(wheels, k, state, model, body, params);
    state.*force = below;
    const double down = heading_step(wheels, k, state, model, body, params);
    state.*force = at;
    return (up - down) / (static_cast<double>(above) - static_cast<double>(below));
  };
  return {slope(&DrivingState::specific_force_x_mps2), slope(&DrivingState::specific_force_y_mps2)};
}

}  // namespace

double white_noise_sigma(const std::vector<double>& channel) {
  if (channel.size() < 3) return 0.0;
  // A few hundred thousand differences fix the median to a fraction of a per cent; a long
  // drive's millions are taken at a stride, not copied whole.
  constexpr std::size_t kEnough = 200000;
  const std::size_t stride = std::max<std::size_t>(1, (channel.size() - 2) / kEnough);
  std::vector<double> second;
  second.reserve((channel.size() - 2) / stride + 1);
  for (std::size_t k = 1; k + 1 < channel.size(); k += stride)
    second.push_back(std::abs(channel[k + 1] - 2.0 * channel[k] + channel[k - 1]));
  // A white sample's second difference has variance 6 sigma^2.
  return normal_sigma_from_absolute(std::move(second)) / std::sqrt(6.0);
}

AccelerometerWalk accelerometer_heading_walk(const WheelStream& wheels, const ImuStream& imu,
                                             const std::vector<DrivingState>& states,
                                             const TyreModel& model, const VehicleBody& body,
                                             const OdometryParams& params) {
  if (states.size() != wheels.size())
    throw std::invalid_argument("accelerometer_heading_walk: one driving state per wheel sample");
  AccelerometerWalk walk{white_noise_sigma(imu.ax_mps2), white_noise_sigma(imu.ay_mps2), 0.0,
                         !wheels.drive_force_n.empty()};
  if (model.plain() || imu.size() < 2 || wheels.size() < 2) return walk;
  // Each accelerometer sample's weight in the heading: a wheel sample's force is the mean over
  // its increment, so each sample inside it carries its share of that sample's sensitivity; an
  // increment without one (a slower accelerometer) interpolates, here its nearest sample. The
  // samples come in order, so each weight is squared once it is complete (not stored: a long
  // drive's accelerometer has millions).
  double sum_x = 0.0, sum_y = 0.0;
  std::size_t pending = imu.size();
  double pending_x = 0.0, pending_y = 0.0;
  const auto add = [&](std::size_t sample, double x, double y) {
    if (sample != pending) {
      sum_x += pending_x * pending_x;
      sum_y += pending_y * pending_y;
      pending = sample;
      pending_x = pending_y = 0.0;
    }
    pending_x += x;
    pending_y += y;
  };
  std::size_t j = 0;
  for (std::size_t k = 1; k < wheels.size(); ++k) {
    const double from = wheels.t_s[k - 1], to = wheels.t_s[k];
    if (to < imu.t_s.front() || from > imu.t_s.back()) continue;  // no accelerometer there
    while (j < imu.size() && imu.t_s[j] <= from) ++j;
    std::size_t inside = 0;
    while (j + inside < imu.size() && imu.t_s[j + inside] <= to) ++inside;
    const Sensitivity s = heading_sensitivity(wheels, k, states[k], model, body, params);
    if (inside == 0) {
      const double mid = 0.5 * (from + to);
      const bool earlier = j == imu.size() || (j > 0 && mid - imu.t_s[j - 1] < imu.t_s[j] - mid);
      add(earlier ? j - 1 : j, s.forward, s.left);
      continue;
    }
    const double share = 1.0 / static_cast<double>(inside);
    for (std::size_t i = j; i < j + inside; ++i) add(i, s.forward * share, s.left * share);
  }
  add(imu.size(), 0.0, 0.0);  // the last sample's weight is complete
  walk.heading_rad = std::sqrt(walk.noise_x_mps2 * walk.noise_x_mps2 * sum_x +
                               walk.noise_y_mps2 * walk.noise_y_mps2 * sum_y);
  return walk;
}

}  // namespace odocal
