#include "odocal/estimation/tick_dequantisation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>

#include "odocal/data/fitted_wheels.hpp"
#include "odocal/estimation/wheel_gaps.hpp"

namespace odocal {
namespace {

// The polynomial a count is fitted with over each window: dead reckoning's line, or the batch's
// quadratic, which follows the heading's curvature where the turn rate changes (a line through
// +-h misses it by h^2/6 times the count's second derivative, a systematic shift of the fitted
// scale) at about 2.25 times the line's noise for the same window.
enum class LocalFit { kLine, kQuadratic };

// The straight line fitted by least squares to the running count over samples [a, b] of `step`
// (step[i]: the count's change into sample i), at j, less the count at j. From the steps
// themselves, so that where the count starts (a block of a long log, or all of it) changes no
// digit.
double line_offset(const std::vector<double>& step, std::size_t a, std::size_t b, std::size_t j) {
  const double m = static_cast<double>(b - a + 1);
  double count = 0.0;  // at i, relative to a
  double at_j = 0.0;
  double sum_i = 0.0, sum_y = 0.0, sum_ii = 0.0, sum_iy = 0.0;
  for (std::size_t i = a; i <= b; ++i) {
    if (i > a) count += step[i];
    if (i == j) at_j = count;
    const double di = static_cast<double>(i) - static_cast<double>(j);
    sum_i += di;
    sum_y += count;
    sum_ii += di * di;
    sum_iy += di * count;
  }
  const double spread = sum_ii - sum_i * sum_i / m;
  const double slope = spread > 0.0 ? (sum_iy - sum_i * sum_y / m) / spread : 0.0;
  return sum_y / m - slope * sum_i / m - at_j;
}

// As line_offset with a quadratic in (i - j); a window too short to hold one takes the line.
// Where a segment's end cuts the window the quadratic is carried out to it (9/m the count's
// variance at the end against the line's 4/m), which moves only the heading across the first or
// last half window: the line there would miss a turn's curvature by more.
double quadratic_offset(const std::vector<double>& step, std::size_t a, std::size_t b,
                        std::size_t j) {
  if (b - a + 1 < 5) return line_offset(step, a, b, j);
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d moments = Eigen::Vector3d::Zero();
  double count = 0.0;
  double at_j = 0.0;
  for (std::size_t i = a; i <= b; ++i) {
    if (i > a) count += step[i];
    if (i == j) at_j = count;
    const double di = static_cast<double>(i) - static_cast<double>(j);
    const Eigen::Vector3d powers(1.0, di, di * di);
    normal.noalias() += powers * powers.transpose();
    moments.noalias() += powers * count;
  }
  return normal.ldlt().solve(moments)(0) - at_j;
}

double fitted_offset(LocalFit fit, const std::vector<double>& step, std::size_t a, std::size_t b,
                     std::size_t j) {
  return fit == LocalFit::kQuadratic ? quadratic_offset(step, a, b, j) : line_offset(step, a, b, j);
}

// Increments [begin, end) of one unbroken segment, through their running count: the local fit
// over +-half_window samples at each one (the line's is the mean where the window is whole; near
// the segment's ends, where it is cut, the fit carries the count's slope to the end, so that a
// segment starting in motion starts on its fitted count, as the rest of it continues).
void smooth_segment(std::vector<double>& increments, std::size_t begin, std::size_t end,
                    LocalFit fit, std::size_t half_window, std::vector<double>& step,
                    std::vector<double>& offset) {
  // Sample j of the segment is begin + j - 1; j = 0, the sample before it, is where it starts.
  const std::size_t n = end - begin;
  step.assign(n + 1, 0.0);
  for (std::size_t j = 1; j <= n; ++j) step[j] = increments[begin + j - 1];
  offset.resize(n + 1);
  for (std::size_t j = 0; j <= n; ++j)
    offset[j] = fitted_offset(fit, step, j > half_window ? j - half_window : 0,
                              std::min(n, j + half_window), j);
  for (std::size_t j = 1; j <= n; ++j)
    increments[begin + j - 1] = step[j] + offset[j] - offset[j - 1];
}

void smooth_wheel(std::vector<double>& increments, const WheelStream& wheels, LocalFit fit,
                  std::size_t half_window, double max_gap_s) {
  if (increments.empty()) return;
  std::vector<double> step, offset;
  // A chain break's increment spans a gap (zero by convention), and so does the increment after
  // a gap that nothing marked (a stream not prepared): it stays as counted, the segments lie on
  // either side.
  std::size_t begin = 1;
  for (std::size_t k = 1; k <= wheels.size(); ++k) {
    const bool segment_ends =
        k == wheels.size() || wheels.breaks_at(k) || wheels.t_s[k] - wheels.t_s[k - 1] > max_gap_s;
    if (!segment_ends) continue;
    if (k > begin) smooth_segment(increments, begin, k, fit, half_window, step, offset);
    begin = k + 1;
  }
}

// The samples that +-half_window_s spans, and the longest step that is not a gap; none where
// the stream is not ticks or too short to smooth.
struct SmoothingWindow {
  std::size_t half_window = 0;
  double max_gap_s = 0.0;
};

std::optional<SmoothingWindow> smoothing_window(const WheelStream& wheels, double half_window_s) {
  if (wheels.unit_rear != WheelUnit::kTicks || !(half_window_s > 0.0) || wheels.size() < 3)
    return std::nullopt;
  const double period_s = median_sample_period_s(wheels);
  if (!(period_s > 0.0)) return std::nullopt;
  const auto half_window = static_cast<std::size_t>(std::lround(half_window_s / period_s));
  if (half_window == 0) return std::nullopt;
  return SmoothingWindow{half_window, kMaxWheelGapPeriods * period_s};
}

}  // namespace

WheelStream dequantised_ticks(WheelStream wheels, double half_window_s) {
  const std::optional<SmoothingWindow> window = smoothing_window(wheels, half_window_s);
  if (!window) return wheels;
  // Each wheel's increments in place; the times and breaks they are cut at are read alongside.
  for (std::vector<double>* wheel :
       {&wheels.rev_rl, &wheels.rev_rr, &wheels.rev_fl, &wheels.rev_fr})
    smooth_wheel(*wheel, wheels, LocalFit::kLine, window->half_window, window->max_gap_s);
  return wheels;
}

std::vector<double> heading_tick_change(const WheelStream& wheels, double half_window_s) {
  const std::optional<SmoothingWindow> window = smoothing_window(wheels, half_window_s);
  if (!window) return {};
  std::vector<double> change(wheels.size());
  for (std::size_t k = 0; k < wheels.size(); ++k) change[k] = wheels.rev_rr[k] - wheels.rev_rl[k];
  smooth_wheel(change, wheels, LocalFit::kQuadratic, window->half_window, window->max_gap_s);
  for (std::size_t k = 0; k < wheels.size(); ++k) change[k] -= wheels.rev_rr[k] - wheels.rev_rl[k];
  return change;
}

WheelStream heading_dequantised_ticks(WheelStream wheels, double half_window_s) {
  const std::vector<double> change = heading_tick_change(wheels, half_window_s);
  if (change.empty()) return wheels;
  const FittedWheels fitted(wheels, change);
  for (std::size_t k = 0; k < wheels.size(); ++k) {
    const WheelIncrement n = fitted.increment(k);
    wheels.rev_rl[k] = n.rev_rl;
    wheels.rev_rr[k] = n.rev_rr;
  }
  return wheels;
}

}  // namespace odocal
