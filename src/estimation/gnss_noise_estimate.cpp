#include "gnss_noise_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "odocal/estimation/median.hpp"

namespace odocal {

GnssNoiseEstimate estimate_gnss_noise(const std::vector<GnssResidualSample>& residuals,
                                      double bin_s) {
  return estimate_gnss_noise(
      [&](const GnssResidualSink& sink) {
        for (const GnssResidualSample& r : residuals) sink(r.t_s, r.error_m);
      },
      bin_s);
}

GnssNoiseEstimate estimate_gnss_noise(const GnssResidualSource& residuals, double bin_s) {
  GnssNoiseEstimate estimate;
  // First pass: the span, and the components' sizes for the outlier limit (single precision is
  // plenty for a median and halves a long log's copy).
  std::vector<float> components;
  double t0 = 0.0, t_end = 0.0;
  residuals([&](double t_s, const Eigen::Vector2d& error) {
    if (components.empty()) t0 = t_s;
    t_end = t_s;
    components.push_back(static_cast<float>(std::abs(error.x())));
    components.push_back(static_cast<float>(std::abs(error.y())));
  });
  if (components.size() < 20) return estimate;
  const double limit = 5.0 * normal_sigma_from_absolute(std::move(components));

  // Total variance, and the means over time bins (the white part averages out within a bin).
  const auto bins = static_cast<std::size_t>((t_end - t0) / bin_s) + 1;
  std::vector<Eigen::Vector2d> bin_sum(bins, Eigen::Vector2d::Zero());
  std::vector<double> bin_squares(bins, 0.0);
  std::vector<int> bin_count(bins, 0);
  double square_sum = 0.0;
  residuals([&](double t_s, const Eigen::Vector2d& error) {
    if (!(error.cwiseAbs().maxCoeff() <= limit)) {
      ++estimate.outliers;
      return;
    }
    ++estimate.fixes;
    square_sum += error.squaredNorm();
    const auto b = std::min(static_cast<std::size_t>((t_s - t0) / bin_s), bins - 1);
    bin_sum[b] += error;
    bin_squares[b] += error.squaredNorm();
    ++bin_count[b];
  });
  if (estimate.fixes < 10) return estimate;
  const double variance = square_sum / (2.0 * static_cast<double>(estimate.fixes));
  estimate.total_sigma_m = std::sqrt(variance);
  estimate.white_sigma_m = estimate.total_sigma_m;
  // The white part directly: the scatter of the fixes around their bin's mean (a correlated
  // error hardly moves within a bin). Needs bins with several fixes.
  double within = 0.0, within_dof = 0.0;
  for (std::size_t b = 0; b < bins; ++b) {
    if (bin_count[b] < 2) continue;
    within += bin_squares[b] - bin_sum[b].squaredNorm() / bin_count[b];
    within_dof += 2.0 * (bin_count[b] - 1);
  }
  const std::optional<double> white_variance =
      within_dof >= 20.0 ? std::optional<double>(within / within_dof) : std::nullopt;

  // Covariance of bin means `lag` bins apart (per axis, pooled): only the correlated part.
  const auto covariance_at = [&](std::size_t lag) -> std::optional<double> {
    double sum = 0.0;
    int pairs = 0;
    for (std::size_t b = 0; b + lag < bins; ++b) {
      if (bin_count[b] == 0 || bin_count[b + lag] == 0) continue;
      sum += (bin_sum[b] / bin_count[b]).dot(bin_sum[b + lag] / bin_count[b + lag]) / 2.0;
      ++pairs;
    }
    if (pairs < 10) return std::nullopt;
    return sum / pairs;
  };
  const std::optional<double> first = covariance_at(1);
  // A correlated part worth modelling: a tenth of the variance or more.
  if (!first || *first < 0.1 * variance) return estimate;
  if (white_variance) estimate.white_sigma_m = std::sqrt(std::max(*white_variance, 1e-12));

  // ln C(k) = ln sigma_gm^2 - k bin / tau, fitted while C(k) stays above a fifth of C(1) (below
  // that the estimate is mostly noise) and at most a third of the log away.
  double n = 0, sk = 0, skk = 0, sy = 0, sky = 0;
  for (std::size_t lag = 1; lag <= bins / 3; ++lag) {
    const std::optional<double> c = covariance_at(lag);
    if (!c || *c < 0.2 * *first) break;
    const double k = static_cast<double>(lag) * bin_s, y = std::log(*c);
    n += 1;
    sk += k;
    skk += k * k;
    sy += y;
    sky += k * y;
  }
  const double log_span_s = t_end - t0;
  double tau_s, sigma2;
  if (n >= 2 && n * skk - sk * sk > 0.0) {
    const double slope = (n * sky - sk * sy) / (n * skk - sk * sk);
    const double intercept = (sy - slope * sk) / n;
    // A correlation that does not decay within the fit window lasts at least as long as the log.
    tau_s = slope < 0.0 ? -1.0 / slope : log_span_s;
    sigma2 = std::exp(intercept);
  } else {
    tau_s = bin_s;
    sigma2 = *first * std::exp(1.0);
  }
  tau_s = std::clamp(tau_s, bin_s, 10.0 * log_span_s);
  sigma2 = std::min(sigma2, 0.99 * variance);
  estimate.gauss_markov_sigma_m = std::sqrt(sigma2);
  estimate.gauss_markov_tau_s = tau_s;
  if (!white_variance)
    estimate.white_sigma_m = std::sqrt(std::max(variance - sigma2, 0.01 * variance));
  return estimate;
}

}  // namespace odocal
