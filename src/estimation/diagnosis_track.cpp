#include "diagnosis_track.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>

namespace odocal::detail {

WheelTurnScale wheel_turn_scale(const DiagnosisSignals& signals, const std::vector<bool>& use) {
  constexpr double kTurningRadps = 0.1;
  constexpr std::size_t kMinTurning = 50;
  // The scale at rest speed is an extrapolation along v^2 from the turns driven: it holds where
  // the log turns slowly for a while, and not from a log that turns only fast. On Hockenheim's
  // racing line (11-12 s of turning below 10 m/s, the start's) the driven inner wheel's slip,
  // which grows with the force and the load transfer beyond v^2, made the wheels turn 1.53
  // times the gyro's rate at rest speed (rear-driven; 1.17 with a driver who shares the grip)
  // on the stated track. The built-in circuit turns below 10 m/s for 72 s, the urban drive 44 s.
  constexpr double kSlowMps = 10.0, kMinSlowTurningS = 20.0;
  WheelTurnScale scale{std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::infinity(), 0};
  if (signals.gyro_radps.empty()) return scale;
  // wheel yaw rate = a gyro + b gyro v^2 + c v + d
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  Eigen::Vector4d right = Eigen::Vector4d::Zero();
  double yy = 0.0;
  std::size_t n = 0, slow_turning = 0;
  for (std::size_t k = 0; k < signals.size(); ++k) {
    const double gyro = signals.gyro_radps[k];
    const double wheels = signals.wheel_yaw_rate_radps[k];
    const double v = signals.gnss_speed_mps[k];
    if (!use[k] || !std::isfinite(gyro) || !std::isfinite(wheels) || !std::isfinite(v)) continue;
    const Eigen::Vector4d x(gyro, gyro * v * v, v, 1.0);
    normal += x * x.transpose();
    right += x * wheels;
    yy += wheels * wheels;
    ++n;
    if (std::abs(gyro) > kTurningRadps) {
      ++scale.turning;
      if (v < kSlowMps) ++slow_turning;
    }
  }
  if (scale.turning < kMinTurning || n <= 4) return scale;
  if (static_cast<double>(slow_turning) * signals.step_s < kMinSlowTurningS) return scale;
  const Eigen::LDLT<Eigen::Matrix4d> solver(normal);
  if (solver.info() != Eigen::Success) return scale;
  const Eigen::Vector4d coefficients = solver.solve(right);
  const double residual_sum = yy - coefficients.dot(right);
  const double variance = std::max(residual_sum, 0.0) / static_cast<double>(n - 4);
  const Eigen::Matrix4d covariance = variance * solver.solve(Eigen::Matrix4d::Identity());
  if (!(covariance(0, 0) >= 0.0)) return scale;
  scale.at_rest = coefficients(0);
  scale.sigma = std::sqrt(covariance(0, 0));
  return scale;
}

}  // namespace odocal::detail
