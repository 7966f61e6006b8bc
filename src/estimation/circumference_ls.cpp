#include "odocal/estimation/circumference_ls.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <cmath>

#include "hot_loop.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/stepwise_cos_sin.hpp"

namespace odocal {
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
    if (wheels.breaks_at(reference.first_wheel_index + i)) {  // a gap: no row spans it
      window.setZero();
      in_window = 0;
      continue;
    }
    const WheelIncrement n = wheels.increment(reference.first_wheel_index + i);
    const Pose2& previous = x_hat[i - 1];
    const Pose2& target = reference.poses[i];
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

ODOCAL_HOT_LOOP CircumferenceFit fit_circumferences(const WheelStream& wheels,
                                                    const ReferenceTrajectory& reference,
                                                    const std::vector<Pose2>& x_hat,
                                                    double track_width_m,
                                                    const Eigen::Vector3d& weights,
                                                    int window_samples) {
  // The augmented system [sqrt(W) Phi | sqrt(W) z], one allocation per fit. Its QR factor is
  // [[R, d], [0, rho]]: R c = d is the least-squares solution and rho^2 the residual sum.
  const std::size_t samples = x_hat.empty() ? 0 : x_hat.size() - 1;
  const std::size_t windows = (samples + static_cast<std::size_t>(window_samples) - 1) /
                              static_cast<std::size_t>(window_samples);
  Eigen::Matrix<double, Eigen::Dynamic, 3> system =
      Eigen::Matrix<double, Eigen::Dynamic, 3>::Zero(static_cast<Eigen::Index>(3 * windows), 3);
  Eigen::Index rows = 0;
  for_each_row(wheels, reference, x_hat, track_width_m, weights, window_samples,
               [&](double a0, double a1, double b) { system.row(rows++) << a0, a1, b; });
  // Zero rows change nothing; they give a short system the three rows the factor needs.
  if (system.rows() < 3) system.conservativeResizeLike(Eigen::MatrixX3d::Zero(3, 3));
  const Eigen::HouseholderQR<Eigen::MatrixX3d> qr(system);
  const Eigen::Matrix3d factor = qr.matrixQR().topRows<3>().triangularView<Eigen::Upper>();

  CircumferenceFit fit;
  fit.rows = static_cast<std::size_t>(rows);
  const Eigen::Matrix2d R = factor.topLeftCorner<2, 2>();
  const Eigen::JacobiSVD<Eigen::Matrix2d> svd(R);
  const double smallest = svd.singularValues()(1);
  fit.condition_number = smallest > 0.0 ? svd.singularValues()(0) / smallest : INFINITY;
  if (!(smallest > 0.0)) {
    fit.circumference_m.setConstant(NAN);
    fit.covariance.setConstant(NAN);
    return fit;
  }
  fit.circumference_m = R.triangularView<Eigen::Upper>().solve(factor.col(2).head<2>());
  const double residual_ss = factor(2, 2) * factor(2, 2);
  const double dof = static_cast<double>(fit.rows) - 2.0;
  const double variance = dof > 0 ? residual_ss / dof : NAN;
  fit.residual_rms = std::sqrt(residual_ss / static_cast<double>(fit.rows));
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
