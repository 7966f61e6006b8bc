#pragma once
// Angle helpers. Headings are radians, counter-clockwise from world +x (east); see
// docs/conventions.md.

#include <cmath>
#include <numbers>

namespace odocal {

// Wraps an angle to (-pi, pi].
inline double wrap_angle(double angle_rad) {
  // Most callers pass differences that are already in range; std::remainder is slow.
  if (angle_rad > -std::numbers::pi && angle_rad <= std::numbers::pi) return angle_rad;
  double wrapped = std::remainder(angle_rad, 2.0 * std::numbers::pi);
  if (wrapped <= -std::numbers::pi) wrapped += 2.0 * std::numbers::pi;
  return wrapped;
}

// Smallest signed difference a - b, in (-pi, pi].
inline double angle_difference(double a_rad, double b_rad) { return wrap_angle(a_rad - b_rad); }

inline double deg_from_rad(double angle_rad) { return angle_rad * 180.0 / std::numbers::pi; }
inline double rad_from_deg(double angle_deg) { return angle_deg * std::numbers::pi / 180.0; }

}  // namespace odocal
