#pragma once
// Ordinary least squares by its normal equations, a row at a time: the doctor's regressions of
// one signal on a few others over a log's 10 Hz grid (the track's turn scale, the IMU's and the
// antenna's places), with each coefficient's standard error from the residuals.

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>

namespace odocal::detail {

template <int N>
class NormalEquations {
 public:
  using Row = Eigen::Matrix<double, N, 1>;

  // y = row . coefficients + error
  void add(const Row& row, double y) {
    normal_ += row * row.transpose();
    right_ += row * y;
    y_squares_ += y * y;
    ++rows_;
  }
  std::size_t rows() const { return rows_; }

  struct Fit {
    Row coefficients;
    Row sigma;  // standard errors: NaN where the residuals' variance gives none
  };
  // The coefficients and their standard errors from the residuals' variance over rows - N degrees
  // of freedom, times `rows_per_independent` where that many consecutive rows share one error
  // (means over overlapping windows). Nothing with N rows or fewer, or a singular system.
  std::optional<Fit> solve(double rows_per_independent = 1.0) const {
    if (rows_ <= static_cast<std::size_t>(N)) return std::nullopt;
    const Eigen::LDLT<Eigen::Matrix<double, N, N>> solved(normal_);
    if (solved.info() != Eigen::Success) return std::nullopt;
    Fit fit;
    fit.coefficients = solved.solve(right_);
    const double variance =
        std::max(0.0, y_squares_ - fit.coefficients.dot(right_)) / (static_cast<double>(rows_) - N);
    for (int i = 0; i < N; ++i)
      fit.sigma(i) = std::sqrt(variance * solved.solve(Row::Unit(i))(i) * rows_per_independent);
    return fit;
  }

 private:
  Eigen::Matrix<double, N, N> normal_ = Eigen::Matrix<double, N, N>::Zero();
  Row right_ = Row::Zero();
  double y_squares_ = 0.0;
  std::size_t rows_ = 0;
};

}  // namespace odocal::detail
