#include "odocal/estimation/circumference_ls.hpp"

#include <Eigen/SVD>
#include <cmath>

#include "odocal/model/angle.hpp"
#include "odocal/model/stepwise_cos_sin.hpp"

namespace odocal {
namespace {

// Upper-triangular [R | d] of a growing least-squares problem, updated by Givens rotations.
class GivensLeastSquares {
 public:
  void add_row(double a0, double a1, double b) {
    ++rows_;
    double row[3] = {a0, a1, b};
    for (int j = 0; j < 2; ++j) {
      if (row[j] == 0.0) continue;
      // Entries are revolution counts and metres: far from overflow, so no need for hypot's
      // scaling, which costs as much as the rest of the rotation.
      const double r = std::sqrt(R_(j, j) * R_(j, j) + row[j] * row[j]);
      const double c = R_(j, j) / r, s = row[j] / r;
      for (int col = j; col < 3; ++col) {
        const double upper = R_(j, col);
        R_(j, col) = c * upper + s * row[col];
        row[col] = -s * upper + c * row[col];
      }
    }
    residual_ss_ += row[2] * row[2];
  }
  Eigen::Matrix2d R() const { return R_.leftCols<2>(); }
  Eigen::Vector2d d() const { return R_.col(2); }
  double residual_ss() const { return residual_ss_; }
  std::size_t rows() const { return rows_; }

 private:
  Eigen::Matrix<double, 2, 3> R_ = Eigen::Matrix<double, 2, 3>::Zero();
  double residual_ss_ = 0.0;
  std::size_t rows_ = 0;
};

}  // namespace

namespace {

// Feeds the (windowed) rows of eq. 12 to add_row(a_rl, a_rr, z).
template <typename AddRow>
void for_each_row(const WheelStream& wheels, const ReferenceTrajectory& reference,
                  const std::vector<Pose2>& x_hat, double track_width_m,
                  const Eigen::Vector3d& weights, int window_samples, AddRow&& add_row) {
  const Eigen::Vector3d sqrt_w = weights.cwiseSqrt();
  // Sum of the window's rows: [phi_x | z_x], [phi_y | z_y], [phi_yaw | z_yaw].
  Eigen::Matrix3d window = Eigen::Matrix3d::Zero();
  int in_window = 0;
  StepwiseCosSin heading_cos_sin;
  const auto flush = [&] {
    for (int r = 0; r < 3; ++r)
      add_row(sqrt_w(r) * window(r, 0), sqrt_w(r) * window(r, 1), sqrt_w(r) * window(r, 2));
    window.setZero();
    in_window = 0;
  };
  for (std::size_t i = 1; i < x_hat.size(); ++i) {
    const WheelIncrement n = wheels.increment(reference.first_wheel_index + i);
    const Pose2& previous = x_hat[i - 1];
    const Pose2& target = reference.poses.pose[i];
    const auto [c, s] = heading_cos_sin(previous.z());
    window.row(0) +=
        Eigen::RowVector3d(0.5 * n.rev_rl * c, 0.5 * n.rev_rr * c, target.x() - previous.x());
    window.row(1) +=
        Eigen::RowVector3d(0.5 * n.rev_rl * s, 0.5 * n.rev_rr * s, target.y() - previous.y());
    window.row(2) += Eigen::RowVector3d(-n.rev_rl / track_width_m, n.rev_rr / track_width_m,
                                        angle_difference(target.z(), previous.z()));
    if (++in_window == window_samples) flush();
  }
  if (in_window > 0) flush();
}

}  // namespace

CircumferenceFit fit_circumferences(const WheelStream& wheels, const ReferenceTrajectory& reference,
                                    const std::vector<Pose2>& x_hat, double track_width_m,
                                    const Eigen::Vector3d& weights, int window_samples) {
  GivensLeastSquares ls;
  for_each_row(wheels, reference, x_hat, track_width_m, weights, window_samples,
               [&](double a0, double a1, double b) { ls.add_row(a0, a1, b); });
  CircumferenceFit fit;
  fit.rows = ls.rows();
  const Eigen::Matrix2d R = ls.R();
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(R);
  const double smallest = svd.singularValues()(1);
  fit.condition_number = smallest > 0.0 ? svd.singularValues()(0) / smallest : INFINITY;
  if (!(smallest > 0.0)) {
    fit.circumference_m.setConstant(NAN);
    fit.covariance.setConstant(NAN);
    return fit;
  }
  fit.circumference_m = R.triangularView<Eigen::Upper>().solve(ls.d());
  const double dof = static_cast<double>(fit.rows) - 2.0;
  const double variance = dof > 0 ? ls.residual_ss() / dof : NAN;
  fit.residual_rms = std::sqrt(ls.residual_ss() / static_cast<double>(fit.rows));
  const Eigen::Matrix2d R_inv = R.triangularView<Eigen::Upper>().solve(Eigen::Matrix2d::Identity());
  fit.covariance = variance * R_inv * R_inv.transpose();
  return fit;
}

CircumferenceFit fit_common_scale(const WheelStream& wheels, const ReferenceTrajectory& reference,
                                  const std::vector<Pose2>& x_hat, double track_width_m,
                                  const Eigen::Vector3d& weights, int window_samples,
                                  const Eigen::Vector2d& c_ratio) {
  // One unknown: the normal equation is a scalar division, exact to rounding.
  double aa = 0.0, ab = 0.0, bb = 0.0;
  std::size_t rows = 0;
  for_each_row(wheels, reference, x_hat, track_width_m, weights, window_samples,
               [&](double a0, double a1, double b) {
                 const double a = a0 * c_ratio(0) + a1 * c_ratio(1);
                 aa += a * a;
                 ab += a * b;
                 bb += b * b;
                 ++rows;
               });
  CircumferenceFit fit;
  fit.rows = rows;
  if (!(aa > 0.0)) {
    fit.circumference_m.setConstant(NAN);
    fit.covariance.setConstant(NAN);
    fit.condition_number = INFINITY;
    return fit;
  }
  const double k = ab / aa;
  const double residual_ss = std::max(0.0, bb - k * ab);
  const double variance = rows > 1 ? residual_ss / static_cast<double>(rows - 1) : NAN;
  fit.circumference_m = k * c_ratio;
  fit.covariance = variance / aa * c_ratio * c_ratio.transpose();
  fit.condition_number = 1.0;
  fit.residual_rms = std::sqrt(residual_ss / static_cast<double>(rows));
  return fit;
}

}  // namespace odocal
