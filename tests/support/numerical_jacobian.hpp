#pragma once
// Central-difference Jacobian, used to check every analytic Jacobian in odocal.

#include <Eigen/Core>

namespace odocal::testing {

// d f / d x at x, for f: R^N -> R^M given as a callable taking Eigen::Matrix<double, N, 1>.
template <int M, int N, typename Function>
Eigen::Matrix<double, M, N> numerical_jacobian(Function&& f, const Eigen::Matrix<double, N, 1>& x,
                                               double step = 1e-6) {
  Eigen::Matrix<double, M, N> jacobian;
  for (int i = 0; i < N; ++i) {
    Eigen::Matrix<double, N, 1> plus = x;
    Eigen::Matrix<double, N, 1> minus = x;
    plus[i] += step;
    minus[i] -= step;
    jacobian.col(i) = (f(plus) - f(minus)) / (2.0 * step);
  }
  return jacobian;
}

}  // namespace odocal::testing
