#include "odocal/estimation/interpolation.hpp"

#include <algorithm>

#include "odocal/model/angle.hpp"

namespace odocal {
namespace {

struct Bracket {
  std::size_t lower;
  double fraction;  // of the way from lower to lower + 1
};

std::optional<Bracket> bracket(const std::vector<double>& t_s, double at_s) {
  if (t_s.empty() || at_s < t_s.front() || at_s > t_s.back()) return std::nullopt;
  if (t_s.size() == 1) return Bracket{0, 0.0};
  const auto upper = std::upper_bound(t_s.begin(), t_s.end(), at_s);
  const std::size_t lower =
      std::min(static_cast<std::size_t>(upper - t_s.begin()), t_s.size() - 1) - 1;
  return Bracket{lower, (at_s - t_s[lower]) / (t_s[lower + 1] - t_s[lower])};
}

}  // namespace

std::optional<double> interpolate_linear(const std::vector<double>& t_s,
                                         const std::vector<double>& values, double at_s) {
  const auto b = bracket(t_s, at_s);
  if (!b) return std::nullopt;
  if (b->fraction == 0.0) return values[b->lower];
  return values[b->lower] + b->fraction * (values[b->lower + 1] - values[b->lower]);
}

std::optional<double> interpolate_angle(const std::vector<double>& t_s,
                                        const std::vector<double>& angles_rad, double at_s) {
  const auto b = bracket(t_s, at_s);
  if (!b) return std::nullopt;
  if (b->fraction == 0.0) return wrap_angle(angles_rad[b->lower]);
  const double step = angle_difference(angles_rad[b->lower + 1], angles_rad[b->lower]);
  return wrap_angle(angles_rad[b->lower] + b->fraction * step);
}

std::optional<Pose2> interpolate_pose(const PoseStream& poses, double t_s) {
  const auto b = bracket(poses.t_s, t_s);
  if (!b) return std::nullopt;
  const Pose2& a = poses.pose[b->lower];
  if (b->fraction == 0.0) return a;
  const Pose2& c = poses.pose[b->lower + 1];
  Pose2 result = a + b->fraction * (c - a);
  result.z() = a.z() + b->fraction * angle_difference(c.z(), a.z());
  return result;
}

WindowSum window_sum(const std::vector<double>& t_s, const std::vector<double>& values,
                     double from_s, double to_s) {
  const auto first = std::lower_bound(t_s.begin(), t_s.end(), from_s);
  const auto last = std::upper_bound(first, t_s.end(), to_s);
  WindowSum window;
  for (auto it = first; it != last; ++it) {
    const double value = values[static_cast<std::size_t>(it - t_s.begin())];
    window.sum += value;
    window.sum_squares += value * value;
  }
  window.count = static_cast<std::size_t>(last - first);
  return window;
}

}  // namespace odocal
