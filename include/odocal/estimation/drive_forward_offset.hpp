#pragma once
// The accelerometer's forward offset measured over the drive itself, for a log with too few stops
// to measure it standing (docs/tyre-model.md, "The accelerometer's forward offset"). An
// accelerometer at the centre of gravity reads ax = dv/dt - w vy + offset (its own lateral
// speed vy: the rear axle's side slip speed plus w b, b the centre of gravity ahead of the rear
// axle). Over a stretch without an IMU gap the time integral of dv/dt is the speed gained, so the
// wheels' slip and the driver's acceleration cancel: only the speeds at the stretch's two ends
// are needed, and the turn's w^2 b and the side slip's k ay^2 are left to account for. The slope's
// gravity is out where the hills were projected with the GNSS altitude, and averages out over a
// flat loop that ends where it began; elsewhere the drive cannot tell it from the offset.

#include <cmath>
#include <optional>
#include <utility>

#include "odocal/data/log.hpp"
#include "odocal/model/odometry_model.hpp"
#include "odocal/model/tyre_model.hpp"

namespace odocal {

// Time integrals over IMU stretches without a gap; they add over stretches and blocks.
struct DriveForwardSums {
  double duration_s{};
  double squared_steps_s2{};          // sum of dt^2: the white noise's share of the mean
  double forward_less_gain{};         // the integral of ax less the speed gained, m/s
  double lateral{};                   // of ay, m/s
  double lateral_squared{};           // of ay^2, m^2/s^3
  double turn_squared{};              // of wz^2, rad^2/s
  double distance_m{};                // the wheels' (absolute) over the stretches
  double accelerometer_noise_mps2{};  // white noise per sample, the largest of the blocks'
  void add(const DriveForwardSums& other);
};

// Over the IMU samples in [from_s, to_s): the stretches between IMU gaps, each from its first to
// its last sample that has the wheels' speed (over 1 s at the nominal parameters, no chain break
// inside), where that spans at least 5 s.
DriveForwardSums drive_forward_sums(const Log& log, const OdometryParams& nominal, double from_s,
                                    double to_s);

// How the slope's gravity is known to the drive's mean, if at all.
enum class DriveSlope {
  kProjected,   // the GNSS altitude's grade was taken out of ax
  kClosedLoop,  // flat-projected nothing, but the drive ends where it began
};

struct DriveForwardOffset {
  double forward_mps2{};
  double sigma_mps2{};
  double duration_s{};
  double distance_m{};
  bool removed{};  // from ax where it stands out (forward_offset_stands_out), as the stops'
  // 1 sigma of what is left in ax.
  double left_sigma_mps2() const {
    return removed ? sigma_mps2 : std::hypot(forward_mps2, sigma_mps2);
  }
};

// The drive's offset and its 1 sigma: the noise's share, the side slip known to within half its
// textbook value, the accelerometer's place known to +-0.5 m along the car, its yaw to 1 deg,
// and the slope's gravity (the altitude's 3 m at either end over the distance; over a closed loop,
// 0.03 m/s^2 for a grade that the car climbs more slowly than it descends). Nothing without 30 s
// and 200 m of stretches, or where the slope is not known.
std::optional<DriveForwardOffset> drive_forward_offset(const DriveForwardSums& sums,
                                                       const VehicleBody& body,
                                                       std::optional<DriveSlope> slope);

// The measure over a log read in blocks (prepared_blocks.hpp): each block's own span adds its
// sums, and the slope is known where every block's grade was projected, or none was and the drive
// is back within 50 m of its start (the median of 10 fixes at either end, so that one outlier
// neither opens nor closes the loop).
class DriveForwardMeasure {
 public:
  DriveForwardMeasure(const OdometryParams& nominal, const VehicleBody& body)
      : nominal_(nominal), body_(body) {}
  // [from_s, to_s) of `context` (a block with its margins); `projected`: its grade's gravity
  // was taken out of ax.
  void add(const Log& context, double from_s, double to_s, bool projected);
  std::optional<DriveForwardOffset> measure() const;

 private:
  OdometryParams nominal_;
  VehicleBody body_;
  DriveForwardSums sums_;
  bool all_projected_ = true, any_projected_ = false;
  std::optional<std::pair<double, double>> start_xy_, end_xy_;  // GNSS, m
};

}  // namespace odocal
