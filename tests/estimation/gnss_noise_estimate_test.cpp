// The GNSS error seen in residuals: white and Gauss-Markov parts recovered from synthetic series
// with known sigma and correlation time.

#include "estimation/gnss_noise_estimate.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace odocal {
namespace {

std::vector<GnssResidualSample> series(double white_m, double gm_m, double tau_s, double rate_hz,
                                       double duration_s, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  const double dt = 1.0 / rate_hz, phi = tau_s > 0 ? std::exp(-dt / tau_s) : 0.0;
  Eigen::Vector2d bias(gm_m * normal(rng), gm_m * normal(rng));
  std::vector<GnssResidualSample> out;
  for (double t = 0.0; t < duration_s; t += dt) {
    bias =
        phi * bias + gm_m * std::sqrt(1.0 - phi * phi) * Eigen::Vector2d(normal(rng), normal(rng));
    out.push_back({t, bias + white_m * Eigen::Vector2d(normal(rng), normal(rng))});
  }
  return out;
}

TEST(GnssNoiseEstimate, WhiteNoiseHasNoCorrelatedPart) {
  const GnssNoiseEstimate e = estimate_gnss_noise(series(3.0, 0.0, 0.0, 50.0, 600.0, 1));
  EXPECT_NEAR(e.total_sigma_m, 3.0, 0.05);
  EXPECT_EQ(e.gauss_markov_sigma_m, 0.0);
  EXPECT_NEAR(e.white_sigma_m, 3.0, 0.05);
}

TEST(GnssNoiseEstimate, RecoversAGaussMarkovErrorUnderWhiteNoise) {
  for (const double tau : {10.0, 30.0, 60.0}) {
    SCOPED_TRACE(tau);
    const GnssNoiseEstimate e = estimate_gnss_noise(series(0.5, 2.0, tau, 10.0, 3000.0, 2));
    EXPECT_NEAR(e.gauss_markov_sigma_m, 2.0, 0.6);
    EXPECT_GT(e.gauss_markov_tau_s, 0.5 * tau);
    EXPECT_LT(e.gauss_markov_tau_s, 2.0 * tau);
    EXPECT_NEAR(e.white_sigma_m, 0.5, 0.3);
  }
}

TEST(GnssNoiseEstimate, OutliersAreLeftOut) {
  std::vector<GnssResidualSample> r = series(1.0, 0.0, 0.0, 10.0, 300.0, 3);
  for (std::size_t k = 0; k < r.size(); k += 50) r[k].error_m.x() += 40.0;
  const GnssNoiseEstimate e = estimate_gnss_noise(r);
  EXPECT_EQ(e.outliers, (r.size() + 49) / 50);
  EXPECT_NEAR(e.total_sigma_m, 1.0, 0.05);
}

}  // namespace
}  // namespace odocal
