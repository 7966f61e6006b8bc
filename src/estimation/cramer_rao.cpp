#include "odocal/estimation/cramer_rao.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

#include "odocal/model/odometry_model.hpp"

namespace odocal {
namespace {

using Sensitivity = Eigen::Matrix<double, 3, 5>;  // d pose / d theta
using Information = Eigen::Matrix<double, 5, 5>;

// Walks a sorted measurement time list alongside the wheel samples: hands every time that falls
// in [t_begin, t_end) to `use` with its interpolation weight.
class MeasurementCursor {
 public:
  explicit MeasurementCursor(const std::vector<double>& t_s) : t_s_(t_s) {}

  template <typename Use>
  void advance(double t_begin, double t_end, bool last_interval, Use&& use) {
    while (next_ < t_s_.size() && t_s_[next_] < t_begin) ++next_;  // before the wheel span
    while (next_ < t_s_.size() &&
           (t_s_[next_] < t_end || (last_interval && t_s_[next_] == t_end))) {
      use(next_, t_end > t_begin ? (t_s_[next_] - t_begin) / (t_end - t_begin) : 0.0);
      ++next_;
    }
  }

 private:
  const std::vector<double>& t_s_;
  std::size_t next_ = 0;
};

// Whitens the measurements against the quantisation noise: a Kalman filter of the noise state
// z = [pose error (3), current count errors (2)] applied to the sensitivity columns instead of
// data. Each measurement adds nu^T F^-1 nu (nu: the columns' innovation, F: its covariance) to
// the Fisher information; with exact counts nu = S and F = R, the plain sum.
class QuantisationWhitener {
 public:
  explicit QuantisationWhitener(double sigma_rev) : variance_(sigma_rev * sigma_rev) {
    P_.bottomRightCorner<2, 2>() = variance_ * Eigen::Matrix2d::Identity();  // the start counts
  }

  // Rows `first`.. of the pose observed with white noise `sigma`; returns the information.
  template <int Rows>
  Information observe(const Eigen::Matrix<double, Rows, 5>& sensitivity, int first, double sigma) {
    const double noise = sigma * sigma;
    if (variance_ == 0.0) return sensitivity.transpose() * sensitivity / noise;
    const Eigen::Matrix<double, Rows, 5> innovation =
        sensitivity - X_.template middleRows<Rows>(first);
    Eigen::Matrix<double, Rows, Rows> F = P_.template block<Rows, Rows>(first, first);
    F.diagonal().array() += noise;
    const Eigen::Matrix<double, Rows, Rows> F_inverse = F.inverse();
    const Eigen::Matrix<double, 5, Rows> gain = P_.template middleCols<Rows>(first) * F_inverse;
    X_ += gain * innovation;
    P_ -= gain * P_.template middleRows<Rows>(first);
    P_ = 0.5 * (P_ + P_.transpose()).eval();
    return innovation.transpose() * F_inverse * innovation;
  }

  // One wheel increment: the pose error propagates with J_pose and takes the increment's count
  // error, new minus previous cumulative error, through J_wheels.
  void step(const OdometryJacobianPose& J_pose, const OdometryJacobianWheels& J_wheels) {
    if (variance_ == 0.0) return;
    Eigen::Matrix<double, 5, 5> A = Eigen::Matrix<double, 5, 5>::Zero();
    A.topLeftCorner<3, 3>() = J_pose;
    A.topRightCorner<3, 2>() = -J_wheels;
    Eigen::Matrix<double, 5, 2> B;
    B << J_wheels, Eigen::Matrix2d::Identity();
    X_ = (A * X_).eval();
    P_ = (A * P_ * A.transpose() + variance_ * B * B.transpose()).eval();
  }

 private:
  double variance_;
  Eigen::Matrix<double, 5, 5> X_ = Eigen::Matrix<double, 5, 5>::Zero();  // noise-state columns
  Eigen::Matrix<double, 5, 5> P_ = Eigen::Matrix<double, 5, 5>::Zero();
};

}  // namespace

CramerRaoBound circumference_cramer_rao_bound(const Log& log, const OdometryParams& params,
                                              const Pose2& start, const CramerRaoOptions& options) {
  CramerRaoBound bound;
  const WheelStream& wheels = log.wheels;
  Information fisher = Information::Zero();
  MeasurementCursor gnss(log.gnss.t_s);
  static const std::vector<double> kNoTimes;
  const bool use_heading = options.use_heading && log.heading.has_value();
  MeasurementCursor heading(use_heading ? log.heading->t_s : kNoTimes);
  QuantisationWhitener whitener(options.quantisation_sigma_rev);

  Pose2 pose = start;
  Sensitivity S = Sensitivity::Zero();
  S.leftCols<3>().setIdentity();
  OdometryJacobianPose J_pose;
  OdometryJacobianWheels J_wheels;
  OdometryJacobianParams J_params;
  const auto observe_gnss = [&](std::size_t j, const Sensitivity& at) {
    const double sigma = log.gnss.sigma_m.empty() ? options.gnss_sigma_m : log.gnss.sigma_m[j];
    fisher += whitener.observe<2>(at.topRows<2>(), 0, sigma);
    ++bound.gnss_used;
  };
  const auto observe_heading = [&](const Sensitivity& at) {
    fisher += whitener.observe<1>(at.row(2), 2, options.heading_sigma_rad);
    ++bound.heading_used;
  };
  for (std::size_t k = 0; k + 1 < wheels.size(); ++k) {
    pose = predict_pose(
        pose, wheels.increment(k + 1), params, 0.0,
        {.J_pose_pose = &J_pose, .J_pose_wheels = &J_wheels, .J_pose_params = &J_params});
    Sensitivity S_next = J_pose * S;
    S_next.rightCols<2>() += J_params.leftCols<2>();
    const auto at = [&](double weight) { return ((1.0 - weight) * S + weight * S_next).eval(); };
    // Measurements in [t_k, t_k+1) take the quantisation noise of sample k: it moves by
    // centimetres per sample.
    gnss.advance(wheels.t_s[k], wheels.t_s[k + 1], false,
                 [&](std::size_t j, double weight) { observe_gnss(j, at(weight)); });
    heading.advance(wheels.t_s[k], wheels.t_s[k + 1], false,
                    [&](std::size_t, double weight) { observe_heading(at(weight)); });
    whitener.step(J_pose, J_wheels);
    S = S_next;
  }
  const double t_end = wheels.t_s.back();  // measurements at the last wheel sample
  gnss.advance(t_end, t_end, true, [&](std::size_t j, double) { observe_gnss(j, S); });
  heading.advance(t_end, t_end, true, [&](std::size_t, double) { observe_heading(S); });

  // Unknowns differ in scale by orders of magnitude: invert the unit-diagonal form.
  const Eigen::Matrix<double, 5, 1> diagonal = fisher.diagonal();
  bound.condition_number = std::numeric_limits<double>::infinity();
  bound.sigma_c_rl_m = bound.sigma_c_rr_m = std::numeric_limits<double>::infinity();
  if ((diagonal.array() <= 0.0).any()) return bound;
  const Eigen::Matrix<double, 5, 1> scale = diagonal.cwiseSqrt().cwiseInverse();
  const Information scaled = scale.asDiagonal() * fisher * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Information> eigen(scaled, Eigen::EigenvaluesOnly);
  const double smallest = eigen.eigenvalues()(0);
  if (smallest <= 0.0) return bound;
  bound.condition_number = eigen.eigenvalues()(4) / smallest;
  const Information scaled_inverse = scaled.ldlt().solve(Information::Identity());
  bound.covariance = scale.asDiagonal() * scaled_inverse * scale.asDiagonal();
  bound.sigma_c_rl_m = std::sqrt(bound.covariance(3, 3));
  bound.sigma_c_rr_m = std::sqrt(bound.covariance(4, 4));
  return bound;
}

}  // namespace odocal
