#include "batch_observability.hpp"

#include <fmt/format.h>

#include <cmath>

#include "odocal/model/angle.hpp"

namespace odocal {

LogCoverage log_coverage(const Log& log, const MotionCoverage& motion) {
  LogCoverage coverage;
  coverage.distance_m = motion.distance_m;
  coverage.duration_s = motion.moving_s;
  coverage.left_turning_deg = deg_from_rad(motion.left_turning_rad);
  coverage.right_turning_deg = deg_from_rad(motion.right_turning_rad);
  coverage.has_heading = log.heading.has_value() && log.heading->size() > 0;
  coverage.has_gyro = log.imu.has_value() && log.imu->size() > 1;
  return coverage;
}

std::string unidentified_reason(const std::string& name, const LogCoverage& c, bool used) {
  const std::string turns =
      fmt::format("left {:.0f} deg, right {:.0f} deg", c.left_turning_deg, c.right_turning_deg);
  if (name == "circumference_rl_m" || name == "circumference_rr_m") {
    if (c.distance_m < 2000.0) {
      return fmt::format(
          "too short: {:.0f} m driven; millimetre circumferences need a few km under GNSS",
          c.distance_m);
    }
    if (!c.has_heading && !c.has_gyro) {
      return "no heading reference (no heading.csv, no imu.csv): the left/right difference rests "
             "on the GNSS course alone; record the gyro or a heading";
    }
    return fmt::format("the GNSS is too noisy or too sparse for this drive ({:.0f} m, {})",
                       c.distance_m, turns);
  }
  if (name == "track_width_m") {
    return fmt::format(
        "needs more turns ({}): the track width only shows in turns, drive full circles both "
        "ways",
        turns);
  }
  if (name == "gyro_bias_radps") {
    if (!used) return "no gyro: the log has no imu.csv";
    return fmt::format("too short ({:.0f} s) to tell a gyro bias from the turns", c.duration_s);
  }
  if (name == "heading_bias_rad") {
    if (!used) return "no heading reference: the log has no heading.csv";
    return "the heading is too noisy for its bias; a longer drive helps";
  }
  if (name == "lever_arm_x_m" || name == "lever_arm_y_m") {
    return fmt::format(
        "needs more turning ({}): a GNSS antenna offset only shows when the vehicle rotates",
        turns);
  }
  if (name.starts_with("tyre_")) {
    const std::string what = name == "tyre_speed_s2pm2"           ? "a range of speeds"
                             : name == "tyre_lateral_s2pm"        ? "turns at speed, both ways"
                             : name == "tyre_drive_s2pm"          ? "accelerations"
                             : name == "tyre_brake_s2pm"          ? "braking"
                             : name == "tyre_drive_lateral_s4pm2" ? "accelerating out of turns"
                             : name == "tyre_brake_lateral_s4pm2" ? "braking into turns"
                             : name == "tyre_load_s2pm"      ? "turns and accelerations at speed"
                             : name == "tyre_drive_slip"     ? "driving force: accelerations, speed"
                             : name == "tyre_brake_slip"     ? "braking"
                             : name == "tyre_side_slip_s2pm" ? "lateral acceleration"
                                                             : "turns";
    return fmt::format(
        "the drive has too little of what shows it ({}); set tyre_model: none or drive more of "
        "it",
        what);
  }
  if (name == "latency_s") {
    return "needs speed and turns: a GNSS latency only shows as a lag along the velocity";
  }
  return "not identifiable from this log";
}

}  // namespace odocal
