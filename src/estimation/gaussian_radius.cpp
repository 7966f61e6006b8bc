#include "gaussian_radius.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "odocal/error.hpp"

namespace odocal {

double gaussian_radius_probability(const Eigen::Matrix2d& covariance, double radius_m) {
  if (radius_m <= 0.0) return 0.0;
  const Eigen::Vector2d variances =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(covariance, Eigen::EigenvaluesOnly)
          .eigenvalues()
          .cwiseMax(0.0);
  if (variances.maxCoeff() <= 0.0) return 1.0;
  // In the whitened plane z (e = sqrt(variances) .* z) the disc is an ellipse; along each
  // direction theta of z its edge lies at rho(theta), and a standard normal's radius stays below
  // rho with probability 1 - exp(-rho^2 / 2). The integrand is smooth and periodic: the
  // trapezoid rule over a quarter (it is symmetric) converges geometrically.
  constexpr int kSteps = 64;
  double sum = 0.0;
  for (int k = 0; k < kSteps; ++k) {
    const double theta = 0.5 * std::numbers::pi * (k + 0.5) / kSteps;
    const double spread = variances(0) * std::cos(theta) * std::cos(theta) +
                          variances(1) * std::sin(theta) * std::sin(theta);
    sum += spread > 0.0 ? 1.0 - std::exp(-0.5 * radius_m * radius_m / spread) : 1.0;
  }
  return sum / kSteps;
}

double gaussian_radius_median(const std::vector<Eigen::Matrix2d>& covariances,
                              const std::vector<double>& scales) {
  if (covariances.empty() || covariances.size() != scales.size())
    throw Error("gaussian_radius_median: one scale per covariance, at least one of each");
  if (std::any_of(scales.begin(), scales.end(), [](double s) { return !(s > 0.0); }))
    throw Error("gaussian_radius_median: every scale must be positive");
  const auto probability = [&](double radius) {
    double sum = 0.0;
    for (std::size_t i = 0; i < covariances.size(); ++i)
      sum += gaussian_radius_probability(covariances[i], radius * scales[i]);
    return sum / static_cast<double>(covariances.size());
  };
  // Bracket by the largest RMS over its scale (beyond 3 of it: probability > 1/2 for every
  // element), then bisect.
  double high = 0.0;
  for (std::size_t i = 0; i < covariances.size(); ++i)
    high = std::max(high, 3.0 * std::sqrt(std::max(covariances[i].trace(), 0.0)) / scales[i]);
  if (high <= 0.0) return 0.0;
  double low = 0.0;
  for (int iteration = 0; iteration < 60 && high - low > 1e-9 * high; ++iteration) {
    const double middle = 0.5 * (low + high);
    (probability(middle) < 0.5 ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

}  // namespace odocal
