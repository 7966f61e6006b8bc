#pragma once
// The length of a zero-mean 2-D Gaussian error: how often it stays inside a radius, and the radius
// that half of a set of such errors stay inside (each its own covariance, weighted alike). Used to
// say what end error a reference's own uncertainty makes in held-out windows (drift_validation).

#include <Eigen/Core>
#include <vector>

namespace odocal {

// P(|e| <= radius_m) for e ~ N(0, covariance); covariance symmetric positive semi-definite.
double gaussian_radius_probability(const Eigen::Matrix2d& covariance, double radius_m);

// The r with mean_i P(|e_i| / scale_i <= r) = 1/2, e_i ~ N(0, covariances[i]): the median that
// the whole set's lengths, each divided by its scale (1, or a window's distance), would show.
// Throws Error for an empty set, sizes that differ or a scale that is not positive.
double gaussian_radius_median(const std::vector<Eigen::Matrix2d>& covariances,
                              const std::vector<double>& scales);

}  // namespace odocal
