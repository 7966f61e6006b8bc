#include "odocal/estimation/motion_coverage.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace odocal {
namespace {

// Heading change of the gyro over [t0, t1], its samples held (zero-order) until the next one.
double gyro_heading_change(const ImuStream& imu, double t0, double t1) {
  auto k = static_cast<std::size_t>(std::upper_bound(imu.t_s.begin(), imu.t_s.end(), t0) -
                                    imu.t_s.begin());
  if (k > 0) --k;
  double change = 0.0;
  for (; k < imu.size() && imu.t_s[k] < t1; ++k) {
    const double next = k + 1 < imu.size() ? imu.t_s[k + 1] : t1;
    const double overlap = std::min(next, t1) - std::max(imu.t_s[k], t0);
    if (overlap > 0.0) change += imu.wz_radps[k] * overlap;
  }
  return change;
}

}  // namespace

OptionTable<MotionCoverageOptions> MotionCoverageOptions::fields() {
  using O = MotionCoverageOptions;
  static const std::array<OptionField<O>, 3> kFields{{
      {"moving_speed_mps", "m/s", 0.0, 10.0, "the vehicle counts as moving above this wheel speed",
       &O::moving_speed_mps},
      {"window_s", "s", 0.01, 60.0, "turning is measured over windows of this length",
       &O::window_s},
      {"turn_rate_radps", "rad/s", 0.0, 10.0,
       "a window counts as turning when its mean yaw rate exceeds this", &O::turn_rate_radps},
  }};
  return kFields;
}

std::string MotionCoverageOptions::validate() const { return check_option_ranges(fields(), *this); }

MotionCoverage motion_coverage(const Log& log, const OdometryParams& nominal, double begin_s,
                               double end_s, const MotionCoverageOptions& options) {
  MotionCoverage coverage;
  const WheelStream& wheels = log.wheels;
  const bool gyro = log.imu && log.imu->size() > 1;
  coverage.turning_source = gyro ? "gyro" : "wheels";
  // Windows of consecutive wheel samples: distance, moving time and heading change of each.
  double window_start = -1.0, window_yaw = 0.0, window_distance = 0.0, last_t = 0.0;
  bool window_moving = false;
  const auto close_window = [&](double window_end) {
    const double duration = window_end - window_start;
    if (!window_moving || duration <= 0.0) return;
    // Over a window, not a sample: a sample's few ticks would add their quantisation to v^2.
    const double speed = window_distance / duration;
    coverage.distance_speed_squared_m3ps2 += window_distance * speed * speed;
    const double yaw = gyro ? gyro_heading_change(*log.imu, window_start, window_end) : window_yaw;
    if (std::abs(yaw) / duration < options.turn_rate_radps) return;
    (yaw > 0.0 ? coverage.left_turning_rad : coverage.right_turning_rad) += std::abs(yaw);
  };
  for (std::size_t k = 1; k < wheels.size(); ++k) {
    if (wheels.t_s[k - 1] < begin_s || wheels.t_s[k] > end_s) continue;
    const double dt = wheels.t_s[k] - wheels.t_s[k - 1];
    const BodyIncrement step = body_increment(wheels.increment(k), nominal);
    const bool moving = std::abs(step.distance_m) > options.moving_speed_mps * dt;
    if (moving) {
      coverage.distance_m += std::abs(step.distance_m);
      coverage.moving_s += dt;
    }
    if (window_start < 0.0 || wheels.t_s[k] - window_start > options.window_s) {
      if (window_start >= 0.0) close_window(wheels.t_s[k - 1]);
      window_start = wheels.t_s[k - 1];
      window_yaw = 0.0;
      window_distance = 0.0;
      window_moving = false;
    }
    window_yaw += step.yaw_rad;
    window_distance += std::abs(step.distance_m);
    window_moving = window_moving || moving;
    last_t = wheels.t_s[k];
  }
  if (window_start >= 0.0) close_window(last_t);
  return coverage;
}

}  // namespace odocal
