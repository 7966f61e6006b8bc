#include "batch_speed_residual.hpp"

#include <algorithm>

namespace odocal::batch {

std::optional<DopplerInterval> doppler_interval(const GnssStream& gnss, double begin_s,
                                                double end_s, double max_gap_s,
                                                double min_speed_mps) {
  const std::vector<double>& t = gnss.t_s;
  const std::vector<double>& v = gnss.speed_mps;
  if (v.size() != t.size() || t.size() < 2 || end_s <= begin_s) return std::nullopt;
  const auto after_begin = std::upper_bound(t.begin(), t.end(), begin_s);
  if (after_begin == t.begin() || after_begin == t.end()) return std::nullopt;
  const std::size_t first = static_cast<std::size_t>(after_begin - t.begin()) - 1;
  const auto at_end = std::lower_bound(after_begin, t.end(), end_s);
  if (at_end == t.end()) return std::nullopt;
  const std::size_t last = static_cast<std::size_t>(at_end - t.begin());

  DopplerInterval interval;
  for (std::size_t j = first; j <= last; ++j) {
    if (v[j] < min_speed_mps) return std::nullopt;
    interval.fixes.push_back(j);
    interval.weights_s.push_back(0.0);
  }
  const auto speed_at = [&](std::size_t j, double time) {
    const double share = (time - t[j]) / (t[j + 1] - t[j]);
    return (1.0 - share) * v[j] + share * v[j + 1];
  };
  for (std::size_t j = first; j < last; ++j) {
    if (t[j + 1] - t[j] > max_gap_s) return std::nullopt;
    const double from = std::max(t[j], begin_s), to = std::min(t[j + 1], end_s);
    const double a = (from - t[j]) / (t[j + 1] - t[j]), b = (to - t[j]) / (t[j + 1] - t[j]);
    // The trapezoid of the interpolated speed over [from, to], split onto its two fixes.
    interval.weights_s[j - first] += (to - from) * (2.0 - a - b) / 2.0;
    interval.weights_s[j + 1 - first] += (to - from) * (a + b) / 2.0;
    if (t[j] <= begin_s && begin_s < t[j + 1]) interval.speed_change_mps -= speed_at(j, begin_s);
    if (t[j] < end_s && end_s <= t[j + 1]) interval.speed_change_mps += speed_at(j, end_s);
  }
  for (const double w : interval.weights_s) interval.sum_squared_weights_s2 += w * w;
  return interval;
}

}  // namespace odocal::batch
