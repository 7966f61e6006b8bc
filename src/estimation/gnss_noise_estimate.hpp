#pragma once
// The GNSS error a fit actually saw: from the residuals of the fixes (metres, per axis) at their
// times, a white part and a first-order Gauss-Markov part (sigma, correlation time). The batch
// calibration re-solves with it when it differs from the configured noise, so that its sigma
// covers the error when the configuration is wrong (docs/batch-calibration.md).

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace odocal {

struct GnssResidualSample {
  double t_s{};
  // Fix minus fitted position. Unaligned: 24 bytes a fix instead of 32 (one per fix of a log).
  Eigen::Matrix<double, 2, 1, Eigen::DontAlign> error_m = Eigen::Vector2d::Zero();
};

struct GnssNoiseEstimate {
  double total_sigma_m{};  // RMS per axis, outliers left out
  double white_sigma_m{};
  double gauss_markov_sigma_m{};  // 0: no correlated part found
  double gauss_markov_tau_s{};
  std::size_t fixes{};     // used
  std::size_t outliers{};  // beyond 5 robust sigmas, left out
};

// Calls its argument once per residual, in time order (it is called twice: a long log's
// residuals need not be held).
using GnssResidualSink = std::function<void(double t_s, const Eigen::Vector2d& error_m)>;
using GnssResidualSource = std::function<void(const GnssResidualSink&)>;

// `bin_s`: the correlation is measured between means over bins of this length (1 s: the white
// part averages out within a bin and is independent between bins).
GnssNoiseEstimate estimate_gnss_noise(const GnssResidualSource& residuals, double bin_s = 1.0);
GnssNoiseEstimate estimate_gnss_noise(const std::vector<GnssResidualSample>& residuals,
                                      double bin_s = 1.0);

}  // namespace odocal
