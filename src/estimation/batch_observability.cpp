#include "batch_observability.hpp"

#include <fmt/format.h>

#include <cmath>

#include "odocal/model/angle.hpp"

namespace odocal {

LogCoverage log_coverage(const Log& log, const ReferenceTrajectory& reference) {
  LogCoverage coverage;
  const auto& poses = reference.poses;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    coverage.distance_m += (poses.pose[i].head<2>() - poses.pose[i - 1].head<2>()).norm();
    const double turn = deg_from_rad(angle_difference(poses.pose[i].z(), poses.pose[i - 1].z()));
    (turn > 0 ? coverage.left_turning_deg : coverage.right_turning_deg) += std::abs(turn);
  }
  if (poses.size() > 1) coverage.duration_s = poses.t_s.back() - poses.t_s.front();
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
  if (name == "latency_s") {
    return "needs speed and turns: a GNSS latency only shows as a lag along the velocity";
  }
  return "not identifiable from this log";
}

}  // namespace odocal
