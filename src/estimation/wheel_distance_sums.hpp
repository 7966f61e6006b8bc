// The wheels' distance, heading and odometry-chain breaks summed from a stream's start at given
// parameters, for differences over time windows: the speed the accelerometer's forward offset is
// read against (accelerometer_offset.cpp, drive_forward_offset.cpp).
#pragma once

#include <optional>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/model/odometry_model.hpp"

namespace odocal {

class WheelDistanceSums {
 public:
  WheelDistanceSums(const WheelStream& wheels, const OdometryParams& params)
      : wheels_(wheels), distance_(wheels.size()), heading_(wheels.size()), breaks_(wheels.size()) {
    for (std::size_t k = 1; k < wheels.size(); ++k) {
      const BodyIncrement step = body_increment(wheels.increment(k), params);
      distance_[k] = distance_[k - 1] + step.distance_m;
      heading_[k] = heading_[k - 1] + step.yaw_rad;
      breaks_[k] = breaks_[k - 1] + (wheels.breaks_at(k) ? 1.0 : 0.0);
    }
  }
  // Each sum at t_s (signed distance m, heading rad, breaks counted); none outside the stream.
  std::optional<double> distance_at(double t_s) const { return at(distance_, t_s); }
  std::optional<double> heading_at(double t_s) const { return at(heading_, t_s); }
  std::optional<double> breaks_at(double t_s) const { return at(breaks_, t_s); }
  // The speed over [t_s - window_s / 2, t_s + window_s / 2]; none outside the stream or across a
  // chain break.
  std::optional<double> speed(double t_s, double window_s) const {
    const double behind = t_s - 0.5 * window_s, ahead = t_s + 0.5 * window_s;
    const auto d0 = distance_at(behind), d1 = distance_at(ahead);
    const auto b0 = breaks_at(behind), b1 = breaks_at(ahead);
    if (!d0 || !d1 || !b0 || !b1 || *b1 != *b0) return std::nullopt;
    return (*d1 - *d0) / window_s;
  }

 private:
  std::optional<double> at(const std::vector<double>& sums, double t_s) const {
    return interpolate_linear(wheels_.t_s, sums, t_s);
  }

  const WheelStream& wheels_;
  std::vector<double> distance_, heading_, breaks_;
};

}  // namespace odocal
