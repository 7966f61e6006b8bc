#include "odocal/estimation/road_grade.hpp"

#include <algorithm>
#include <cmath>

#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/rolled_distance.hpp"
#include "odocal/model/gravity.hpp"

namespace odocal {
namespace {

double cos_pitch(double grade) { return 1.0 / std::sqrt(1.0 + grade * grade); }

}  // namespace

namespace {

double interpolate(const std::vector<double>& values, double step_m, double distance_m) {
  if (values.empty()) return 0.0;
  const double position =
      std::clamp(distance_m / step_m, 0.0, static_cast<double>(values.size() - 1));
  const auto below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (position - static_cast<double>(below)) * (values[above] - values[below]);
}

}  // namespace

double GradeProfile::at_distance(double distance_m) const {
  return interpolate(grade, step_m, distance_m);
}

double GradeProfile::cos_pitch_at(double distance_m) const {
  return 1.0 / std::sqrt(1.0 + interpolate(grade_squared, step_m, distance_m));
}

double GradeProfile::scale_variance() const {
  if (grade.empty()) return 0.0;
  const double length_m = step_m * static_cast<double>(grade.size());
  double sum = 0.0;
  for (std::size_t p = 0; p < grade.size(); ++p) sum += grade[p] * grade[p] * grade_variance[p];
  return window_m * step_m / (length_m * length_m) * sum;
}

double GradeProfile::typical_max_grade() const {
  if (grade.empty()) return 0.0;
  std::vector<double> magnitude(grade.size());
  for (std::size_t p = 0; p < grade.size(); ++p) magnitude[p] = std::abs(grade[p]);
  const auto at = magnitude.begin() +
                  static_cast<std::ptrdiff_t>(0.95 * static_cast<double>(magnitude.size() - 1));
  std::nth_element(magnitude.begin(), at, magnitude.end());
  return *at;
}

double GradeProfile::length_excess() const {
  if (grade.empty()) return 0.0;
  double horizontal = 0.0, spatial = 0.0;
  for (const double g2 : grade_squared) {
    horizontal += 1.0;
    spatial += std::sqrt(1.0 + g2);
  }
  return spatial / horizontal - 1.0;
}

std::optional<GradeProfile> grade_from_gnss_altitude(const Log& log, const OdometryParams& nominal,
                                                     double window_m) {
  const GnssStream& gnss = log.gnss;
  const WheelStream& wheels = log.wheels;
  if (gnss.altitude_m.empty() || wheels.size() < 2) return std::nullopt;
  GradeProfile profile;
  profile.step_m = std::max(1.0, window_m / 20.0);
  profile.wheel_distance_m = rolled_distance_m(wheels, nominal);
  const double total_m = profile.wheel_distance_m.back();
  if (total_m < window_m) return std::nullopt;
  // Each fix placed at the distance driven when it was taken.
  std::vector<double> fix_distance, fix_altitude;
  for (std::size_t j = 0; j < gnss.size(); ++j) {
    const auto d = interpolate_linear(wheels.t_s, profile.wheel_distance_m, gnss.t_s[j]);
    if (!d || !std::isfinite(gnss.altitude_m[j])) continue;
    fix_distance.push_back(*d);
    fix_altitude.push_back(gnss.altitude_m[j]);
  }
  if (fix_distance.size() < 20) return std::nullopt;
  const auto points = static_cast<std::size_t>(total_m / profile.step_m) + 1;
  profile.grade.assign(points, 0.0);
  profile.grade_squared.assign(points, 0.0);
  profile.grade_variance.assign(points, 0.0);
  profile.window_m = window_m;
  std::size_t first = 0;
  for (std::size_t p = 0; p < points; ++p) {
    const double centre = static_cast<double>(p) * profile.step_m;
    while (first < fix_distance.size() && fix_distance[first] < centre - 0.5 * window_m) ++first;
    double n = 0, sd = 0, sdd = 0, sz = 0, sdz = 0, szz = 0;
    for (std::size_t j = first; j < fix_distance.size(); ++j) {
      const double d = fix_distance[j] - centre;  // centred: no cancellation far from the start
      if (d > 0.5 * window_m) break;
      const double z = fix_altitude[j] - fix_altitude[first];
      n += 1;
      sd += d;
      sdd += d * d;
      sz += z;
      sdz += d * z;
      szz += z * z;
    }
    const double spread = sdd - sd * sd / n;
    // Too few fixes, or all at one place (standing): the neighbours' grade carries on.
    if (n < 10 || spread < n * window_m * window_m / 100.0) {
      profile.grade[p] = p > 0 ? profile.grade[p - 1] : 0.0;
      profile.grade_squared[p] = p > 0 ? profile.grade_squared[p - 1] : 0.0;
      profile.grade_variance[p] = p > 0 ? profile.grade_variance[p - 1] : 0.0;
      continue;
    }
    const double slope = (sdz - sd * sz / n) / spread;
    const double residual = std::max(0.0, szz - sz * sz / n - slope * (sdz - sd * sz / n));
    profile.grade[p] = slope;
    profile.grade_variance[p] = residual / (n - 2.0) / spread;
  }
  // grade^2 less its variance, unclipped: a clip at zero would bias the flat parts up.
  for (std::size_t p = 0; p < points; ++p) {
    profile.grade_squared[p] =
        std::max(profile.grade[p] * profile.grade[p] - profile.grade_variance[p], -0.5);
  }
  return profile;
}

double slope_gravity_mps2(double grade) { return kGravityMps2 * grade * cos_pitch(grade); }

void project_to_horizontal(Log& log, const GradeProfile& profile) {
  WheelStream& wheels = log.wheels;
  wheels.grade.assign(wheels.size(), static_cast<float>(profile.at_distance(0.0)));
  for (std::size_t k = 1; k < wheels.size(); ++k) {
    const double mid_m = 0.5 * (profile.wheel_distance_m[k] + profile.wheel_distance_m[k - 1]);
    wheels.grade[k] = static_cast<float>(profile.at_distance(mid_m));
    const double c = profile.cos_pitch_at(mid_m);
    const double mean = 0.5 * (wheels.rev_rl[k] + wheels.rev_rr[k]);
    const double half_difference = 0.5 * (wheels.rev_rr[k] - wheels.rev_rl[k]);
    wheels.rev_rl[k] = mean * c - half_difference / c;
    wheels.rev_rr[k] = mean * c + half_difference / c;
  }
  if (!log.imu) return;
  for (std::size_t k = 0; k < log.imu->size(); ++k) {
    const auto d = interpolate_linear(wheels.t_s, profile.wheel_distance_m, log.imu->t_s[k]);
    if (!d) continue;
    log.imu->ax_mps2[k] -= slope_gravity_mps2(profile.at_distance(*d));
    log.imu->wz_radps[k] /= profile.cos_pitch_at(*d);  // turning about the vertical, not the body
  }
}

}  // namespace odocal
