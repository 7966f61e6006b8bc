#include "odocal/sim/speed_profile.hpp"

#include <algorithm>
#include <cmath>

#include "odocal/error.hpp"

namespace odocal::sim {

SpeedProfile::SpeedProfile(const Path& path, const DriverLimits& limits,
                           const std::vector<Stop>& stops,
                           const std::vector<double>& segment_speed_scale, double grid_m) {
  const int points = std::max(2, static_cast<int>(std::ceil(path.length_m() / grid_m)) + 1);
  const double ds = path.length_m() / (points - 1);
  std::vector<double> dwell(points, 0.0);
  std::vector<bool> must_stop(points, false);
  const auto stop_at = [&](double s_m, double dwell_s) {
    const auto i = static_cast<std::size_t>(std::lround(std::clamp(s_m / ds, 0.0, points - 1.0)));
    must_stop[i] = true;
    dwell[i] += dwell_s;
  };
  stop_at(0.0, limits.start_dwell_s);
  stop_at(path.length_m(), limits.start_dwell_s);
  for (double change : path.direction_changes_m()) stop_at(change, 0.5);
  for (const Stop& stop : stops) stop_at(stop.at_m, stop.dwell_s);

  s_m_.resize(points);
  speed_mps_.resize(points);
  std::vector<double> curvature_1pm(points);  // unsigned
  for (int i = 0; i < points; ++i) {
    s_m_[i] = i * ds;
    const PathPoint point = path.at(s_m_[i]);
    curvature_1pm[i] = std::abs(point.curvature_1pm);
    const double scale = segment_speed_scale.empty() ? 1.0 : segment_speed_scale.at(point.segment);
    const double cap =
        scale * (point.direction > 0 ? limits.max_speed_mps : limits.max_reverse_speed_mps);
    const double corner = curvature_1pm[i] > 1e-9
                              ? scale * std::sqrt(limits.max_lateral_acc_mps2 / curvature_1pm[i])
                              : cap;
    speed_mps_[i] = must_stop[i] ? 0.0 : std::min(cap, corner);
  }
  // The share of the longitudinal bound that the turn leaves at grid point i and speed v.
  const auto grip_left = [&](int i, double v) {
    if (!limits.friction_ellipse) return 1.0;
    constexpr double kKept = 0.05;
    const double turn = v * v * curvature_1pm[i] / limits.max_lateral_acc_mps2;
    return std::max(kKept, std::sqrt(std::max(0.0, 1.0 - turn * turn)));
  };
  for (int i = 1; i < points; ++i) {
    const double v = speed_mps_[i - 1];
    double acc = limits.max_acc_mps2 * grip_left(i - 1, v);
    if (limits.max_power_wpkg > 0.0) {
      constexpr double kLowestSpeedMps = 1.0;  // P / v has no bound at rest
      acc = std::min(acc, limits.max_power_wpkg / std::max(v, kLowestSpeedMps));
    }
    speed_mps_[i] = std::min(speed_mps_[i], std::sqrt(v * v + 2.0 * acc * ds));
  }
  for (int i = points - 2; i >= 0; --i) {
    const double v = speed_mps_[i + 1];
    const double brake = limits.max_brake_mps2 * grip_left(i + 1, v);
    speed_mps_[i] = std::min(speed_mps_[i], std::sqrt(v * v + 2.0 * brake * ds));
  }
  arrive_s_.resize(points);
  depart_s_.resize(points);
  arrive_s_[0] = 0.0;
  depart_s_[0] = dwell[0];
  for (int i = 1; i < points; ++i) {
    const double mean_speed = 0.5 * (speed_mps_[i - 1] + speed_mps_[i]);
    if (mean_speed <= 0.0) throw Error("speed profile: two stops closer than the profile grid");
    arrive_s_[i] = depart_s_[i - 1] + ds / mean_speed;
    depart_s_[i] = arrive_s_[i] + dwell[i];
  }
}

MotionState SpeedProfile::at(double t_s) const {
  if (t_s <= depart_s_.front()) return {s_m_.front(), 0.0, 0.0};
  if (t_s >= arrive_s_.back()) return {s_m_.back(), 0.0, 0.0};
  // i: last grid point reached by t_s.
  const std::size_t i = static_cast<std::size_t>(
      std::upper_bound(arrive_s_.begin(), arrive_s_.end(), t_s) - arrive_s_.begin() - 1);
  if (t_s <= depart_s_[i]) return {s_m_[i], 0.0, 0.0};
  const double ds = s_m_[i + 1] - s_m_[i];
  const double v0 = speed_mps_[i];
  const double v1 = speed_mps_[i + 1];
  const double acc = (v1 * v1 - v0 * v0) / (2.0 * ds);
  const double tau = t_s - depart_s_[i];
  return {std::min(s_m_[i] + v0 * tau + 0.5 * acc * tau * tau, s_m_[i + 1]),
          std::max(0.0, v0 + acc * tau), acc};
}

}  // namespace odocal::sim
