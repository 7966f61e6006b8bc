#include "graded_motion.hpp"

#include <algorithm>
#include <cmath>

#include "odocal/model/gravity.hpp"

namespace odocal::sim {
namespace {

constexpr double kGridHz = 200.0;

}  // namespace

GradedMotion::GradedMotion(std::unique_ptr<MotionTruth> flat, const Terrain& terrain,
                           double lap_length_m)
    : flat_(std::move(flat)), hills_(terrain, lap_length_m) {
  // Wheel angles: over each step the wheels' mean turn grows by 1 / cos(pitch) (the 3-D distance)
  // and their difference shrinks by cos(pitch) (the body turns about its tilted vertical).
  grid_step_s_ = 1.0 / kGridHz;
  const auto steps = static_cast<std::size_t>(std::ceil(flat_->duration_s() * kGridHz)) + 1;
  distance_m_.assign(steps, 0.0);
  extra_angle_rl_rad_.assign(steps, 0.0);
  extra_angle_rr_rad_.assign(steps, 0.0);
  TruthSample previous = flat_->at(0.0);
  for (std::size_t i = 1; i < steps; ++i) {
    const TruthSample sample = flat_->at(static_cast<double>(i) * grid_step_s_);
    const double ds = (sample.pose.head<2>() - previous.pose.head<2>()).norm();
    distance_m_[i] = distance_m_[i - 1] + ds;
    const double cos_pitch = Pitch(grade(0.5 * (distance_m_[i] + distance_m_[i - 1]))).cos;
    const double d_rl = sample.wheel_angle_rl_rad - previous.wheel_angle_rl_rad;
    const double d_rr = sample.wheel_angle_rr_rad - previous.wheel_angle_rr_rad;
    const double mean = 0.5 * (d_rl + d_rr), half_difference = 0.5 * (d_rr - d_rl);
    const double mean_extra = mean * (1.0 / cos_pitch - 1.0);
    const double difference_extra = half_difference * (cos_pitch - 1.0);
    extra_angle_rl_rad_[i] = extra_angle_rl_rad_[i - 1] + mean_extra - difference_extra;
    extra_angle_rr_rad_[i] = extra_angle_rr_rad_[i - 1] + mean_extra + difference_extra;
    previous = sample;
  }
}

double GradedMotion::interpolate(const std::vector<double>& values, double t_s) const {
  const double position =
      std::clamp(t_s / grid_step_s_, 0.0, static_cast<double>(values.size() - 1));
  const auto below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (position - static_cast<double>(below)) * (values[above] - values[below]);
}

TruthSample GradedMotion::at(double t_s) const {
  TruthSample sample = flat_->at(t_s);
  const double s = interpolate(distance_m_, t_s);
  const Pitch pitch(grade(s));
  const double cos_pitch = pitch.cos;
  sample.altitude_m = hills_.altitude_m(s);
  sample.wheel_angle_rl_rad += interpolate(extra_angle_rl_rad_, t_s);
  sample.wheel_angle_rr_rad += interpolate(extra_angle_rr_rad_, t_s);
  const double mean = 0.5 * (sample.wheel_rate_rl_radps + sample.wheel_rate_rr_radps);
  const double half_difference = 0.5 * (sample.wheel_rate_rr_radps - sample.wheel_rate_rl_radps);
  sample.wheel_rate_rl_radps = mean / cos_pitch - half_difference * cos_pitch;
  sample.wheel_rate_rr_radps = mean / cos_pitch + half_difference * cos_pitch;
  // Nose up on the way uphill: the forward accelerometer reads g sin(pitch) more.
  sample.ax_mps2 += kGravityMps2 * pitch.sin;
  sample.yaw_rate_radps *= cos_pitch;
  return sample;
}

}  // namespace odocal::sim
