#include "diagnosis_track.hpp"

#include <cmath>
#include <limits>

#include "normal_equations.hpp"

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
  NormalEquations<4> equations;
  std::size_t slow_turning = 0;
  for (std::size_t k = 0; k < signals.size(); ++k) {
    const double gyro = signals.gyro_radps[k];
    const double wheels = signals.wheel_yaw_rate_radps[k];
    const double v = signals.gnss_speed_mps[k];
    if (!use[k] || !std::isfinite(gyro) || !std::isfinite(wheels) || !std::isfinite(v)) continue;
    equations.add({gyro, gyro * v * v, v, 1.0}, wheels);
    if (std::abs(gyro) > kTurningRadps) {
      ++scale.turning;
      if (v < kSlowMps) ++slow_turning;
    }
  }
  if (scale.turning < kMinTurning) return scale;
  if (static_cast<double>(slow_turning) * signals.step_s < kMinSlowTurningS) return scale;
  const auto fit = equations.solve();
  if (!fit || std::isnan(fit->sigma(0))) return scale;
  scale.at_rest = fit->coefficients(0);
  scale.sigma = fit->sigma(0);
  return scale;
}

}  // namespace odocal::detail
