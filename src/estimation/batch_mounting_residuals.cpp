// The mean errors a fit leaves where a sensor's mounting is off what it holds
// (BatchSummary's MountingResiduals; BatchOptions::detect_mounting).
#include <algorithm>
#include <cmath>
#include <vector>

#include "batch_problem.hpp"
#include "sample_mean.hpp"

namespace odocal::batch {

namespace {

// Fewer keyframe intervals than this say nothing of a mean.
constexpr std::size_t kMinIntervals = 10;
// More than this many are sampled at a stride: a pass over every fix of the 10-hour drive added
// 14 s to its 87 s, and an hour of keyframes puts the standard errors far below what matters.
constexpr std::size_t kMaxIntervals = 3600;

// Per keyframe interval, the sum of one error and how many samples it holds.
struct IntervalSums {
  std::vector<double> sum;
  std::vector<std::size_t> count;
  explicit IntervalSums(std::size_t intervals) : sum(intervals, 0.0), count(intervals, 0) {}
  void add(std::size_t interval, double value) {
    sum[interval] += value;
    ++count[interval];
  }
};

struct MeanWithError {
  double mean{}, standard_error{};
  bool measured{};
};

// The mean of the intervals' means and its standard error, widened for their lag-1 correlation
// (an AR(1) sequence's variance of the mean, (1 + rho) / (1 - rho) times the white one's).
// sqrt((1 + rho) / (1 - rho)) for the lag-1 correlation rho of `values` about `centre`.
double correlation_widening(const std::vector<double>& values, double centre) {
  double variance = 0.0, lagged = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    variance += (values[i] - centre) * (values[i] - centre);
    if (i > 0) lagged += (values[i] - centre) * (values[i - 1] - centre);
  }
  const double rho = variance > 0.0 ? std::clamp(lagged / variance, 0.0, 0.99) : 0.0;
  return std::sqrt((1.0 + rho) / (1.0 - rho));
}

MeanWithError mean_of_interval_means(const IntervalSums& sums) {
  std::vector<double> means;
  means.reserve(sums.sum.size());
  for (std::size_t i = 0; i < sums.sum.size(); ++i)
    if (sums.count[i] > 0) means.push_back(sums.sum[i] / static_cast<double>(sums.count[i]));
  if (means.size() < kMinIntervals) return {};
  const SampleMean m = sample_mean(means);
  return {m.mean, m.standard_error * correlation_widening(means, m.mean), true};
}

// Through the origin: the slope of `error` over `turn` and its standard error (widened as above).
MeanWithError slope_over(const std::vector<double>& turn, const std::vector<double>& error) {
  if (turn.size() < kMinIntervals) return {};
  double turn_squared = 0.0, product = 0.0;
  for (std::size_t i = 0; i < turn.size(); ++i) {
    turn_squared += turn[i] * turn[i];
    product += turn[i] * error[i];
  }
  if (!(turn_squared > 0.0)) return {};
  const double slope = product / turn_squared;
  std::vector<double> rest(turn.size());
  double variance = 0.0;
  for (std::size_t i = 0; i < turn.size(); ++i) {
    rest[i] = error[i] - slope * turn[i];
    variance += rest[i] * rest[i];
  }
  variance /= static_cast<double>(turn.size()) - 1.0;
  return {slope, std::sqrt(variance / turn_squared) * correlation_widening(rest, 0.0), true};
}

}  // namespace

MountingResiduals BatchProblem::mounting_residuals() const {
  const std::size_t intervals = keyframes_.size() > 1 ? keyframes_.size() - 1 : 0;
  IntervalSums ahead(intervals), left(intervals), heading(intervals);
  const auto& t = wheels_.t_s;
  for_each_measurement(
      [&](std::size_t fix, std::size_t i, const Eigen::Vector2d& whitened) {
        Eigen::Vector2d error = -white_gnss_sigma(fix) * whitened;  // measured minus fitted
        if (gauss_markov()) error += Eigen::Vector2d(gnss_bias_[i][0], gnss_bias_[i][1]);
        // The heading at the fix, between the keyframes' (a fix sees the vehicle turned by it).
        const double t0 = t[keyframes_[i]], t1 = t[keyframes_[i + 1]];
        const double share =
            t1 > t0 ? std::clamp((log_.gnss.t_s[fix] - fix_lag_s() - t0) / (t1 - t0), 0.0, 1.0)
                    : 0.0;
        const double yaw = poses_[i][2] + share * (poses_[i + 1][2] - poses_[i][2]);
        const double c = std::cos(yaw), s = std::sin(yaw);
        ahead.add(i, c * error.x() + s * error.y());
        left.add(i, -s * error.x() + c * error.y());
      },
      [&](std::size_t i, double whitened) {
        heading.add(i, -sensors_.heading_sigma_rad * whitened);  // measured minus fitted
      },
      std::max<std::size_t>(1, (intervals + kMaxIntervals - 1) / kMaxIntervals));
  MountingResiduals residuals;
  std::vector<double> turn, doppler_error;
  turn.reserve(speed_.size());
  doppler_error.reserve(speed_.size());
  for (std::size_t i = 0; i < std::min(intervals, speed_.size()); ++i) {
    if (!speed_[i]) continue;
    turn.push_back(poses_[i + 1][2] - poses_[i][2]);
    doppler_error.push_back(-speed_whitened(i) * speed_[i]->sigma_m);  // Doppler minus wheels
  }
  if (const MeanWithError slope = slope_over(turn, doppler_error); slope.measured) {
    residuals.doppler = true;
    residuals.doppler_left_m = -slope.mean;
    residuals.doppler_left_standard_error_m = slope.standard_error;
  }
  const MeanWithError x = mean_of_interval_means(ahead), y = mean_of_interval_means(left);
  if (x.measured && y.measured) {
    residuals.gnss = true;
    residuals.gnss_mean_m = {x.mean, y.mean};
    residuals.gnss_standard_error_m = {x.standard_error, y.standard_error};
  }
  if (const MeanWithError h = mean_of_interval_means(heading); h.measured) {
    residuals.heading = true;
    residuals.heading_mean_rad = h.mean;
    residuals.heading_standard_error_rad = h.standard_error;
  }
  return residuals;
}

}  // namespace odocal::batch
