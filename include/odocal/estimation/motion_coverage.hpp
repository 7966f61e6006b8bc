#pragma once
// What a log's motion offers for identifying the wheel parameters, counted only while the
// vehicle moves: the distance driven (the one distance figure every command reports) and the
// turning to either side. Measured on the wheels and the gyro, not on the noisy GNSS/heading
// reference, so that standing still and sensor noise add neither distance nor turning.

#include <string>

#include "odocal/data/log.hpp"
#include "odocal/options/option_fields.hpp"

namespace odocal {

struct MotionCoverageOptions {
  double moving_speed_mps = 0.5;  // the vehicle counts as moving above this wheel speed
  // Turning counts in windows of this length whose mean yaw rate exceeds turn_rate_radps: a gyro
  // or encoder's noise and a gyro's bias stay below it, a real turn is well above.
  double window_s = 1.0;
  double turn_rate_radps = 0.035;  // 2 deg/s

  static OptionTable<MotionCoverageOptions> fields();
  std::string validate() const;  // empty when valid
};

struct MotionCoverage {
  double distance_m{};  // rear-axle midpoint, wheel odometry, nominal circumferences
  double moving_s{};
  double left_turning_rad{};  // sum of counter-clockwise turns (positive)
  double right_turning_rad{};
  std::string turning_source;  // "gyro" (imu.csv) or "wheels"
  // The sum of distance times speed squared over the moving windows: a rolling radius that grows
  // with v^2 rolls the drive on its distance-weighted mean.
  double distance_speed_squared_m3ps2{};

  double turning_rad() const { return left_turning_rad + right_turning_rad; }
  // The distance-weighted mean of v^2 while moving, (m/s)^2; 0 for a log that did not move.
  double mean_square_speed_m2ps2() const {
    return distance_m > 0.0 ? distance_speed_squared_m3ps2 / distance_m : 0.0;
  }
};

// Over the wheel samples with begin_s <= t <= end_s.
MotionCoverage motion_coverage(const Log& log, const OdometryParams& nominal, double begin_s,
                               double end_s, const MotionCoverageOptions& options = {});

}  // namespace odocal
