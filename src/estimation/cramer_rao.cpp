#include "odocal/estimation/cramer_rao.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
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

// Whitens the measurements against the correlated noise: a Kalman filter of the noise state
// z = [pose error (3), current count errors (2), GNSS Gauss-Markov error (2)] applied to the
// sensitivity columns instead of data. Each measurement adds nu^T F^-1 nu (nu: the columns'
// innovation, F: its covariance) to the Fisher information; without correlated noise nu = S and
// F = R, the plain sum.
class CorrelatedNoiseWhitener {
 public:
  using State = Eigen::Matrix<double, 7, 1>;
  using StateMatrix = Eigen::Matrix<double, 7, 7>;

  CorrelatedNoiseWhitener(double count_sigma_rev, double gauss_markov_sigma_m, double tau_s)
      : count_variance_(count_sigma_rev * count_sigma_rev),
        gauss_markov_variance_(gauss_markov_sigma_m * gauss_markov_sigma_m),
        tau_s_(tau_s) {
    P_.block<2, 2>(3, 3) = count_variance_ * Eigen::Matrix2d::Identity();  // the start counts
    P_.block<2, 2>(5, 5) = gauss_markov_variance_ * Eigen::Matrix2d::Identity();  // stationary
  }

  bool correlated() const { return count_variance_ > 0.0 || gauss_markov_variance_ > 0.0; }
  double gauss_markov_variance() const { return gauss_markov_variance_; }

  // Measurement rows with sensitivity S, noise-state rows H and white noise variance.
  template <int Rows>
  Information observe(const Eigen::Matrix<double, Rows, 5>& S,
                      const Eigen::Matrix<double, Rows, 7>& H, double white_variance) {
    if (!correlated()) return S.transpose() * S / white_variance;
    const Eigen::Matrix<double, Rows, 5> innovation = S - H * X_;
    Eigen::Matrix<double, Rows, Rows> F = H * P_ * H.transpose();
    F.diagonal().array() += white_variance;
    const Eigen::Matrix<double, Rows, Rows> F_inverse = F.inverse();
    const Eigen::Matrix<double, 7, Rows> gain = P_ * H.transpose() * F_inverse;
    X_ += gain * innovation;
    P_ -= gain * H * P_;
    P_ = 0.5 * (P_ + P_.transpose()).eval();
    return innovation.transpose() * F_inverse * innovation;
  }

  // One wheel increment over dt_s: the pose error propagates with J_pose and takes the
  // increment's count error (new minus previous cumulative error) through J_wheels; the GNSS
  // error decays by exp(-dt / tau) and is driven to stay stationary.
  void step(const OdometryJacobianPose& J_pose, const OdometryJacobianWheels& J_wheels,
            double dt_s) {
    if (!correlated()) return;
    StateMatrix A = StateMatrix::Zero();
    A.topLeftCorner<3, 3>() = J_pose;
    A.block<3, 2>(0, 3) = -J_wheels;
    const double decay = gauss_markov_variance_ > 0.0 ? std::exp(-dt_s / tau_s_) : 0.0;
    A.block<2, 2>(5, 5) = decay * Eigen::Matrix2d::Identity();
    Eigen::Matrix<double, 7, 2> B = Eigen::Matrix<double, 7, 2>::Zero();
    B.topRows<3>() = J_wheels;
    B.middleRows<2>(3).setIdentity();
    X_ = (A * X_).eval();
    P_ = (A * P_ * A.transpose() + count_variance_ * B * B.transpose()).eval();
    P_.block<2, 2>(5, 5).diagonal().array() += gauss_markov_variance_ * (1.0 - decay * decay);
  }

 private:
  double count_variance_;
  double gauss_markov_variance_;
  double tau_s_;
  Eigen::Matrix<double, 7, 5> X_ = Eigen::Matrix<double, 7, 5>::Zero();  // noise-state columns
  StateMatrix P_ = StateMatrix::Zero();
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
  CorrelatedNoiseWhitener whitener(options.quantisation_sigma_rev,
                                   options.gnss_gauss_markov_sigma_m,
                                   options.gnss_gauss_markov_tau_s);
  Eigen::Matrix<double, 2, 7> H_gnss = Eigen::Matrix<double, 2, 7>::Zero();
  H_gnss.leftCols<2>().setIdentity();
  H_gnss.rightCols<2>().setIdentity();
  Eigen::Matrix<double, 1, 7> H_heading = Eigen::Matrix<double, 1, 7>::Zero();
  H_heading(2) = 1.0;

  Pose2 pose = start;
  Sensitivity S = Sensitivity::Zero();
  S.leftCols<3>().setIdentity();
  OdometryJacobianPose J_pose;
  OdometryJacobianWheels J_wheels;
  OdometryJacobianParams J_params;
  const auto observe_gnss = [&](std::size_t j, const Sensitivity& at) {
    const double sigma = log.gnss.sigma_m.empty() ? options.gnss_sigma_m : log.gnss.sigma_m[j];
    // A fix's sigma is the total; with a Gauss-Markov part, the white part is what remains.
    const double white =
        std::max(sigma * sigma - whitener.gauss_markov_variance(), 1e-3 * sigma * sigma);
    fisher += whitener.observe<2>(at.topRows<2>(), H_gnss, white);
    ++bound.gnss_used;
  };
  const auto observe_heading = [&](const Sensitivity& at) {
    fisher += whitener.observe<1>(at.row(2), H_heading,
                                  options.heading_sigma_rad * options.heading_sigma_rad);
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
    whitener.step(J_pose, J_wheels, wheels.t_s[k + 1] - wheels.t_s[k]);
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
