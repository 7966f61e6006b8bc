#pragma once
// Interpolation of timed poses and positions at arbitrary times, and means over time windows.

#include <optional>
#include <vector>

#include "odocal/data/log.hpp"

namespace odocal {

// Pose at t_s: linear in x, y; yaw along the shortest arc. nullopt outside [t.front, t.back].
std::optional<Pose2> interpolate_pose(const PoseStream& poses, double t_s);

// Linear interpolation of a sampled scalar; nullopt outside the sampled span.
std::optional<double> interpolate_linear(const std::vector<double>& t_s,
                                         const std::vector<double>& values, double at_s);

// As interpolate_linear, for angles: along the shortest arc, result wrapped to (-pi, pi].
std::optional<double> interpolate_angle(const std::vector<double>& t_s,
                                        const std::vector<double>& angles_rad, double at_s);

// The samples of a sampled scalar with time in [from_s, to_s] (bisection on sorted t_s).
struct WindowSum {
  double sum{};
  double sum_squares{};
  std::size_t count{};
  std::optional<double> mean() const {
    return count > 0 ? std::optional<double>(sum / static_cast<double>(count)) : std::nullopt;
  }
};
WindowSum window_sum(const std::vector<double>& t_s, const std::vector<double>& values,
                     double from_s, double to_s);

}  // namespace odocal
