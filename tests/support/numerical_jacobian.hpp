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

// The same for run-time sizes: f maps an Eigen::VectorXd to an Eigen::VectorXd.
template <typename Function>
Eigen::MatrixXd numerical_jacobian(Function&& f, const Eigen::VectorXd& x, double step = 1e-6) {
  Eigen::MatrixXd jacobian;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    Eigen::VectorXd plus = x;
    Eigen::VectorXd minus = x;
    plus[i] += step;
    minus[i] -= step;
    const Eigen::VectorXd column = (f(plus) - f(minus)) / (2.0 * step);
    if (i == 0) jacobian.resize(column.size(), x.size());
    jacobian.col(i) = column;
  }
  return jacobian;
}

}  // namespace odocal::testing
