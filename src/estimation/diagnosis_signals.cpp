#include "diagnosis_signals.hpp"

#include <algorithm>
#include <cmath>

#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/paired_moments.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/tyre_model.hpp"

namespace odocal::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kSmoothS = 1.0;  // wheels and IMU averaged over this window

// Cumulative revolutions at each wheel sample, for distance over any interval.
std::vector<double> cumulative(const std::vector<double>& increments) {
  std::vector<double> sum(increments.size(), 0.0);
  for (std::size_t k = 1; k < increments.size(); ++k) sum[k] = sum[k - 1] + increments[k];
  return sum;
}

double at(const std::vector<double>& t_s, const std::vector<double>& values, double t) {
  return interpolate_linear(t_s, values, t).value_or(kNaN);
}

// Mean of the samples in [from, to] (NaN if none).
double mean_over(const std::vector<double>& t_s, const std::vector<double>& values, double from,
                 double to) {
  return window_sum(t_s, values, from, to).mean().value_or(kNaN);
}

}  // namespace

std::size_t grid_rows(const Log& log, double from_s, double step_s) {
  const double to = std::min(log.wheels.t_s.back(), log.gnss.t_s.back());
  if (!(to > from_s)) return 0;
  return static_cast<std::size_t>((to - from_s) / step_s);
}

DiagnosisSignals diagnosis_signals(const Log& log, double step_s) {
  DiagnosisSignals s;
  s.step_s = step_s;
  const double from = std::max(log.wheels.t_s.front(), log.gnss.t_s.front());
  const double to = std::min(log.wheels.t_s.back(), log.gnss.t_s.back());
  if (!(to - from > 5.0)) return s;
  append_diagnosis_signals(log, from, step_s, 0, grid_rows(log, from, step_s), s);
  return s;
}

void append_diagnosis_signals(const Log& log, double from, double step_s, std::size_t first,
                              std::size_t last, DiagnosisSignals& s) {
  s.step_s = step_s;
  const std::size_t rows = grid_rows(log, from, step_s);
  last = std::min(last, rows);
  if (first >= last) return;
  const OdometryParams nominal = log.vehicle.nominal_params();
  const std::vector<double> rev_rl = cumulative(log.wheels.rev_rl);
  const std::vector<double> rev_rr = cumulative(log.wheels.rev_rr);
  const auto grid_t = [&](std::size_t i) { return from + (static_cast<double>(i) + 0.5) * step_s; };
  // GNSS velocity from the mean positions of the second before and after: a 3 m noise averages
  // down over a 50 Hz second, and a 1-5 Hz receiver still gives a few fixes.
  constexpr double kHalfWindowS = 1.0;
  const auto lag = static_cast<std::size_t>(std::lround(kHalfWindowS / step_s));
  const auto velocity = [&](std::size_t i) {
    const double t = grid_t(i);
    const double x0 = mean_over(log.gnss.t_s, log.gnss.x_m, t - kHalfWindowS, t);
    const double x1 = mean_over(log.gnss.t_s, log.gnss.x_m, t, t + kHalfWindowS);
    const double y0 = mean_over(log.gnss.t_s, log.gnss.y_m, t - kHalfWindowS, t);
    const double y1 = mean_over(log.gnss.t_s, log.gnss.y_m, t, t + kHalfWindowS);
    return std::make_pair((x1 - x0) / kHalfWindowS, (y1 - y0) / kHalfWindowS);
  };
  // Velocities of the rows and of their course-rate neighbours, each once.
  const std::size_t v_first = first >= lag ? first - lag : 0;
  const std::size_t v_last = std::min(rows, last + lag);
  std::vector<std::pair<double, double>> velocities;
  velocities.reserve(v_last - v_first);
  for (std::size_t i = v_first; i < v_last; ++i) velocities.push_back(velocity(i));
  const auto velocity_at = [&](std::size_t i) { return velocities[i - v_first]; };
  for (std::size_t i = first; i < last; ++i) {
    const double t = grid_t(i);
    s.t_s.push_back(t);
    // Wheel distance over a second: one tick of a 96-tick encoder in 0.1 s is a 0.13 rad/s
    // jump of the yaw rate; over a second it is 0.013 rad/s.
    const double a = t - 0.5 * kSmoothS, b = t + 0.5 * kSmoothS;
    s.speed_rl_mps.push_back((at(log.wheels.t_s, rev_rl, b) - at(log.wheels.t_s, rev_rl, a)) *
                             nominal.circumference_rl_m / kSmoothS);
    s.speed_rr_mps.push_back((at(log.wheels.t_s, rev_rr, b) - at(log.wheels.t_s, rev_rr, a)) *
                             nominal.circumference_rr_m / kSmoothS);
    s.wheel_yaw_rate_radps.push_back((s.speed_rr_mps.back() - s.speed_rl_mps.back()) /
                                     nominal.track_width_m);
    const auto [vx, vy] = velocity_at(i);
    s.gnss_speed_mps.push_back(!log.gnss.speed_mps.empty() ? at(log.gnss.t_s, log.gnss.speed_mps, t)
                                                           : std::hypot(vx, vy));
    // The 4 s baseline: wheel distance over it, GNSS chord between the means of its first and
    // last 2 s (centres 2 s before and after).
    constexpr double kLongS = 4.0;
    const double la = t - 0.5 * kLongS, lb = t + 0.5 * kLongS;
    s.speed_long_rl_mps.push_back(
        (at(log.wheels.t_s, rev_rl, lb) - at(log.wheels.t_s, rev_rl, la)) *
        nominal.circumference_rl_m / kLongS);
    s.speed_long_rr_mps.push_back(
        (at(log.wheels.t_s, rev_rr, lb) - at(log.wheels.t_s, rev_rr, la)) *
        nominal.circumference_rr_m / kLongS);
    const double gx0 = mean_over(log.gnss.t_s, log.gnss.x_m, la - 1.0, la + 1.0);
    const double gx1 = mean_over(log.gnss.t_s, log.gnss.x_m, lb - 1.0, lb + 1.0);
    const double gy0 = mean_over(log.gnss.t_s, log.gnss.y_m, la - 1.0, la + 1.0);
    const double gy1 = mean_over(log.gnss.t_s, log.gnss.y_m, lb - 1.0, lb + 1.0);
    const double position_speed = std::hypot(gx1 - gx0, gy1 - gy0) / kLongS;
    s.position_speed_long_mps.push_back(position_speed);
    if (!log.gnss.speed_mps.empty())
      s.doppler_speed_mps.push_back(at(log.gnss.t_s, log.gnss.speed_mps, t));
    // Course rate over 1 s where the GNSS moves (below 2 m/s its course is noise).
    double course_rate = kNaN;
    if (i >= lag && i + lag < rows) {
      const auto [ax, ay] = velocity_at(i - lag);
      const auto [bx, by] = velocity_at(i + lag);
      if (std::hypot(ax, ay) >= 2.0 && std::hypot(bx, by) >= 2.0) {
        course_rate = angle_difference(std::atan2(by, bx), std::atan2(ay, ax)) /
                      (static_cast<double>(2 * lag) * step_s);
      }
    }
    s.gnss_course_rate_radps.push_back(course_rate);
    if (log.imu) {
      // Averaged over the wheels' second, so that both see the same motion.
      const auto smoothed = [&](const std::vector<double>& values) {
        const double mean = mean_over(log.imu->t_s, values, t - 0.5 * kSmoothS, t + 0.5 * kSmoothS);
        return std::isfinite(mean) ? mean : at(log.imu->t_s, values, t);
      };
      s.gyro_radps.push_back(smoothed(log.imu->wz_radps));
      s.ax_mps2.push_back(smoothed(log.imu->ax_mps2));
      s.ay_mps2.push_back(smoothed(log.imu->ay_mps2));
    }
    if (!log.wheels.drive_force_n.empty()) {
      const VehicleBody& body = log.vehicle.body;
      const double speed = 0.5 * (s.speed_rl_mps.back() + s.speed_rr_mps.back());
      const double resistance =
          std::copysign(road_resistance(body, std::abs(speed)).total(), speed);
      const double force = mean_over(log.wheels.t_s, log.wheels.drive_force_n, a, b);
      s.drive_force_mps2.push_back(force / body.mass_kg - resistance);
    }
    if (log.heading) {
      const auto before =
          interpolate_angle(log.heading->t_s, log.heading->heading_rad, t - 0.5 * step_s);
      const auto after =
          interpolate_angle(log.heading->t_s, log.heading->heading_rad, t + 0.5 * step_s);
      s.heading_rate_radps.push_back(before && after ? angle_difference(*after, *before) / step_s
                                                     : kNaN);
      const double chord_turn_rad = (s.speed_long_rr_mps.back() - s.speed_long_rl_mps.back()) *
                                    kLongS / nominal.track_width_m;
      double offset = kNaN;
      const double wheel_speed = 0.5 * (s.speed_long_rl_mps.back() + s.speed_long_rr_mps.back());
      if (position_speed >= DiagnosisSignals::kCourseSpeedMps &&
          wheel_speed >= DiagnosisSignals::kCourseSpeedMps &&
          std::abs(chord_turn_rad) < DiagnosisSignals::kStraightChordRad) {
        if (const auto heading = interpolate_angle(log.heading->t_s, log.heading->heading_rad, t))
          offset = angle_difference(*heading, std::atan2(gy1 - gy0, gx1 - gx0));
      }
      s.heading_minus_course_rad.push_back(offset);
    }
  }
}

double slope_through_origin(const std::vector<double>& x, const std::vector<double>& y,
                            const std::vector<bool>& use, std::size_t min_samples) {
  double xy = 0.0, xx = 0.0;
  std::size_t count = 0;
  for (std::size_t k = 0; k < x.size() && k < y.size(); ++k) {
    if (!use[k] || !std::isfinite(x[k]) || !std::isfinite(y[k])) continue;
    xy += x[k] * y[k];
    xx += x[k] * x[k];
    ++count;
  }
  return count >= min_samples && xx > 0.0 ? xy / xx : kNaN;
}

double correlation(const std::vector<double>& x, const std::vector<double>& y,
                   const std::vector<bool>& use, std::size_t min_samples) {
  PairedMoments moments;
  for (std::size_t k = 0; k < x.size() && k < y.size(); ++k) {
    if (use[k] && std::isfinite(x[k]) && std::isfinite(y[k])) moments.add(x[k], y[k]);
  }
  return moments.count() < min_samples ? kNaN : moments.correlation();
}

namespace {

// The lag from the correlations at shifts -max_shift..max_shift: the peak, refined by a parabola.
Lag lag_at_peak(const std::vector<double>& values, long max_shift, double step_s) {
  Lag lag{kNaN, kNaN, values[static_cast<std::size_t>(max_shift)], kNaN};
  std::size_t best = 0;
  bool found = false;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (std::isfinite(values[i]) && (!found || values[i] > values[best])) {
      best = i;
      found = true;
    }
  }
  if (!found) return lag;
  for (const double value : values) {
    if (std::isfinite(value) && !(value >= lag.trough)) lag.trough = value;
  }
  double offset = 0.0;
  if (best > 0 && best + 1 < values.size() && std::isfinite(values[best - 1]) &&
      std::isfinite(values[best + 1])) {
    const double denominator = values[best - 1] - 2 * values[best] + values[best + 1];
    if (denominator < 0.0) offset = 0.5 * (values[best - 1] - values[best + 1]) / denominator;
  }
  lag.lag_s = (static_cast<double>(best) - static_cast<double>(max_shift) + offset) * step_s;
  lag.peak = values[best];
  return lag;
}

// Correlation of y(t + shift) with x(t) at each shift; with `beside`, the partial correlation
// given beside(t).
Lag lag_of(const std::vector<double>& x, const std::vector<double>& y,
           const std::vector<double>* beside, double step_s, double max_lag_s) {
  const auto max_shift = static_cast<long>(std::lround(max_lag_s / step_s));
  const auto n = static_cast<long>(std::min(x.size(), y.size()));
  std::vector<double> values;
  for (long shift = -max_shift; shift <= max_shift; ++shift) {
    std::vector<double> xs, ys, zs;
    for (long k = std::max(0L, -shift); k < n && k + shift < n; ++k) {
      const auto i = static_cast<std::size_t>(k), j = static_cast<std::size_t>(k + shift);
      const double z = beside ? (*beside)[i] : 0.0;
      if (!std::isfinite(x[i]) || !std::isfinite(y[j]) || !std::isfinite(z)) continue;
      xs.push_back(x[i]);
      ys.push_back(y[j]);
      zs.push_back(z);
    }
    const std::vector<bool> use(xs.size(), true);
    const double xy = correlation(xs, ys, use, 50);
    if (!beside) {
      values.push_back(xy);
      continue;
    }
    const double xz = correlation(xs, zs, use, 50), yz = correlation(ys, zs, use, 50);
    const double rest = (1.0 - xz * xz) * (1.0 - yz * yz);
    values.push_back(rest > 0.0 ? (xy - xz * yz) / std::sqrt(rest) : kNaN);
  }
  return lag_at_peak(values, max_shift, step_s);
}

}  // namespace

Lag cross_correlation_lag(const std::vector<double>& x, const std::vector<double>& y, double step_s,
                          double max_lag_s) {
  return lag_of(x, y, nullptr, step_s, max_lag_s);
}

Lag partial_cross_correlation_lag(const std::vector<double>& x, const std::vector<double>& y,
                                  const std::vector<double>& beside, double step_s,
                                  double max_lag_s) {
  return lag_of(x, y, &beside, step_s, max_lag_s);
}

}  // namespace odocal::detail
