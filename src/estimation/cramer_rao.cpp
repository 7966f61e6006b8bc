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
      use(next_, (t_s_[next_] - t_begin) / (t_end - t_begin));
      ++next_;
    }
  }

 private:
  const std::vector<double>& t_s_;
  std::size_t next_ = 0;
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

  Pose2 pose = start;
  Sensitivity S = Sensitivity::Zero();
  S.leftCols<3>().setIdentity();
  OdometryJacobianPose J_pose;
  OdometryJacobianParams J_params;
  for (std::size_t k = 0; k + 1 < wheels.size(); ++k) {
    pose = predict_pose(pose, wheels.increment(k + 1), params, 0.0,
                        {.J_pose_pose = &J_pose, .J_pose_params = &J_params});
    Sensitivity S_next = J_pose * S;
    S_next.rightCols<2>() += J_params.leftCols<2>();
    const bool last = k + 2 == wheels.size();
    const auto at = [&](double weight) { return ((1.0 - weight) * S + weight * S_next).eval(); };
    gnss.advance(wheels.t_s[k], wheels.t_s[k + 1], last, [&](std::size_t j, double weight) {
      const double sigma = log.gnss.sigma_m.empty() ? options.gnss_sigma_m : log.gnss.sigma_m[j];
      const Eigen::Matrix<double, 2, 5> H = at(weight).topRows<2>();
      fisher += H.transpose() * H / (sigma * sigma);
      ++bound.gnss_used;
    });
    heading.advance(wheels.t_s[k], wheels.t_s[k + 1], last, [&](std::size_t, double weight) {
      const Eigen::Matrix<double, 1, 5> H = at(weight).row(2);
      fisher += H.transpose() * H / (options.heading_sigma_rad * options.heading_sigma_rad);
      ++bound.heading_used;
    });
    S = S_next;
  }

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
