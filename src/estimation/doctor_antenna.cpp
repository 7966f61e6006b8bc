// The doctor's check of the GNSS antenna's place: its side of the car, from the Doppler speed in
// the turns.
#include <fmt/format.h>

#include <cmath>

#include "doctor.hpp"
#include "normal_equations.hpp"

namespace odocal::detail {
namespace {

// Below this the wheels' one-second speed and the Doppler's differ by their noise alone.
constexpr double kMinSpeedMps = 3.0;
// A finding: the side read this far from vehicle.yaml's and 5 standard errors (at most 0.1 m).
constexpr double kMinGapM = 0.2, kMaxSigmaM = 0.1, kSigmas = 5.0;

}  // namespace

void Doctor::check_gnss_place() {
  const auto& doppler = signals_.doppler_speed_mps;
  if (doppler.size() != signals_.size() || has("time.gnss_offset")) return;
  const bool gyro_usable = !signals_.gyro_radps.empty() && !has("imu.yaw_sign") &&
                           !has("imu.yaw_unit") && !has("time.imu_offset");
  const auto& turn = gyro_usable ? signals_.gyro_radps : signals_.wheel_yaw_rate_radps;
  const Eigen::Vector2d stated = facts_.vehicle.gnss_position_m.value_or(Eigen::Vector2d::Zero());
  // An antenna y left of the rear axle's centre runs y w slower than the axle in a left turn, one
  // x ahead swings out by w x: its Doppler speed is |(v - w y, w x)|. The stated x's part taken
  // out, the Doppler less the wheels' speed is fitted on -w (y), the speed (the circumferences'
  // scale), the acceleration (a Doppler lag), the lateral acceleration's square (the drive slip of
  // the cornering drag, which on a drive turning mostly one way the side would otherwise take:
  // the realistic circuit read -0.13 m for an antenna on the centreline, -0.09 m with it) and an
  // offset.
  const std::vector<double> acceleration = wheel_acceleration();
  NormalEquations<5> equations;
  for (std::size_t k = 0; k < signals_.size(); ++k) {
    const double speed = 0.5 * (signals_.speed_rl_mps[k] + signals_.speed_rr_mps[k]);
    const double w = turn[k];
    if (!(speed > kMinSpeedMps) || !std::isfinite(w) || !std::isfinite(doppler[k]) ||
        !std::isfinite(acceleration[k]))
      continue;
    const double swing = w * stated.x();
    const double excess = doppler[k] - speed - 0.5 * swing * swing / speed;
    const double lateral = speed * w;
    equations.add({-w, speed, acceleration[k], lateral * lateral, 1.0}, excess);
  }
  if (equations.rows() < 100) return;
  // The wheels' speed is a one-second mean: the rows of one second share it.
  const auto fit = equations.solve(1.0 / signals_.step_s);
  if (!fit) return;
  const double sigma = fit->sigma(0);
  const double read = fit->coefficients(0), gap = std::abs(read - stated.y());
  if (!(std::isfinite(sigma) && sigma <= kMaxSigmaM && gap >= kMinGapM && gap >= kSigmas * sigma))
    return;
  const std::string side = std::abs(read) < 0.1
                               ? std::string("on the car's centreline")
                               : fmt::format("{:.1f} m {} of the rear axle's centre",
                                             std::abs(read), read > 0.0 ? "left" : "right");
  add("gnss.place", FindingSeverity::kWarning,
      fmt::format("gnss.csv's Doppler speed reads the turns as an antenna {} would; vehicle.yaml "
                  "has gnss_y_m {:.2f} m",
                  side, stated.y()),
      fmt::format(
          "Doppler speed less the wheels' against the {} yaw rate, {} rows from {:.0f} m/s: "
          "y = {:+.2f} +- {:.2f} m",
          gyro_usable ? "gyro's" : "wheels'", equations.rows(), kMinSpeedMps, read, sigma),
      facts_.vehicle.gnss_position_m
          ? "vehicle.yaml's gnss_y_m is not where the antenna is (left of the rear axle's "
            "centre, in metres)"
          : "the antenna is mounted off the car's centreline and vehicle.yaml does not say so: "
            "layer 1 and the batch take the fixes as the rear axle's, and on a drive that turns "
            "mostly one way the antenna's distance as the wheels'",
      fmt::format("vehicle.yaml: gnss_y_m: {:.1f} (better: measure it on the car; gnss_x_m "
                  "too)",
                  read));
}

}  // namespace odocal::detail
