#include "odocal/estimation/start_pose.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <cmath>

#include "odocal/error.hpp"
#include "odocal/estimation/dead_reckoning.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/mounted_position.hpp"

namespace odocal {
namespace {

// Heading at t0 from a least-squares line through heading.csv (unwrapped) over the window.
std::optional<double> heading_at_start(const HeadingStream& heading, double t0, double window_s) {
  double n = 0, sum_t = 0, sum_tt = 0, sum_h = 0, sum_th = 0;
  std::optional<double> previous;
  for (std::size_t k = 0; k < heading.size(); ++k) {
    const double dt = heading.t_s[k] - t0;
    if (dt < 0.0 || dt > window_s) continue;
    const double unwrapped = previous
                                 ? *previous + angle_difference(heading.heading_rad[k], *previous)
                                 : heading.heading_rad[k];
    previous = unwrapped;
    n += 1;
    sum_t += dt;
    sum_tt += dt * dt;
    sum_h += unwrapped;
    sum_th += dt * unwrapped;
  }
  if (n == 0) return interpolate_angle(heading.t_s, heading.heading_rad, t0);
  const double determinant = n * sum_tt - sum_t * sum_t;
  if (n < 2 || determinant <= 1e-12) return wrap_angle(sum_h / n);
  const double rate = (n * sum_th - sum_t * sum_h) / determinant;
  return wrap_angle((sum_h - rate * sum_t) / n);
}

}  // namespace

Pose2 start_pose_from_truth(const PoseStream& truth, double t_s) {
  const auto pose = interpolate_pose(truth, t_s);
  if (!pose) {
    throw InsufficientDataError(
        fmt::format("truth.csv starts at {} s, after the first wheel sample at {} s: it cannot "
                    "give the start pose",
                    truth.t_s.front(), t_s));
  }
  return *pose;
}

Pose2 start_pose_from_gnss(const Log& log, const OdometryParams& params,
                           const GnssStartOptions& options) {
  const double t0 = log.wheels.t_s.front();
  WheelStream window = log.wheels;
  std::size_t samples = 0;
  while (samples < window.size() && window.t_s[samples] <= t0 + options.window_s) ++samples;
  window.t_s.resize(samples);
  window.rev_rl.resize(samples);
  window.rev_rr.resize(samples);
  const PoseStream odometry = dead_reckon(window, params, Pose2::Zero());

  std::vector<std::size_t> fixes;
  for (std::size_t k = 0; k < log.gnss.size(); ++k) {
    if (log.gnss.t_s[k] >= t0 && log.gnss.t_s[k] <= odometry.t_s.back()) fixes.push_back(k);
  }
  if (fixes.empty()) {
    throw InsufficientDataError(fmt::format(
        "no GNSS fix within {} s after the first wheel sample ({} s): cannot place the start",
        options.window_s, t0));
  }
  // The fixes are the antenna's: matched with where the odometry puts it (vehicle.yaml's
  // gnss_x_m, gnss_y_m; else the axle).
  const Eigen::Vector2d antenna = log.vehicle.gnss_position_m.value_or(Eigen::Vector2d::Zero());
  Eigen::Matrix2Xd source(2, fixes.size());
  Eigen::Matrix2Xd target(2, fixes.size());
  for (std::size_t i = 0; i < fixes.size(); ++i) {
    const std::size_t k = fixes[i];
    const Eigen::Index column = static_cast<Eigen::Index>(i);
    source.col(column) = mounted_position(*interpolate_pose(odometry, log.gnss.t_s[k]), antenna);
    target.col(column) = Eigen::Vector2d(log.gnss.x_m[k], log.gnss.y_m[k]);
  }
  const auto spread_m = [](const Eigen::Matrix2Xd& points) {
    return std::sqrt((points.colwise() - points.rowwise().mean()).squaredNorm() /
                     static_cast<double>(points.cols()));
  };

  if (spread_m(source) >= options.min_spread_m && spread_m(target) >= options.min_spread_m) {
    const Eigen::Matrix3d world_T_start = Eigen::umeyama(source, target, false);
    return {world_T_start(0, 2), world_T_start(1, 2),
            std::atan2(world_T_start(1, 0), world_T_start(0, 0))};
  }
  std::optional<double> heading_rad;
  if (log.heading) heading_rad = heading_at_start(*log.heading, t0, options.heading_window_s);
  if (!heading_rad) {
    throw InsufficientDataError(fmt::format(
        "no start heading: odometry or GNSS spread less than {} m over the first {} s (the "
        "vehicle barely moves) and the log has no heading.csv",
        options.min_spread_m, options.window_s));
  }
  const Eigen::Vector2d start =
      (target - Eigen::Rotation2Dd(*heading_rad).toRotationMatrix() * source).rowwise().mean();
  return {start.x(), start.y(), *heading_rad};
}

}  // namespace odocal
