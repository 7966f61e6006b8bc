#pragma once
// What the sensor models sample: the true motion at any time of the drive.

#include "odocal/model/odometry_model.hpp"

namespace odocal::sim {

struct TruthSample {
  Pose2 pose;        // rear-axle midpoint, yaw continuous
  double ax_mps2{};  // body-frame acceleration (specific force, planar): forward
  double ay_mps2{};  // left
  double yaw_rate_radps{};
  double wheel_angle_rl_rad{};  // cumulative, signed
  double wheel_angle_rr_rad{};
  double wheel_rate_rl_radps{};
  double wheel_rate_rr_radps{};
  double altitude_m{};  // of the road under the vehicle (0 on flat terrain)
  // The tyres' total longitudinal force, N: the drive's less the brakes' (the realistic vehicle's
  // command, on the ground along each axle's wheels; the ideal vehicle has none).
  double longitudinal_force_n{};
};

class MotionTruth {
 public:
  virtual ~MotionTruth() = default;
  virtual double duration_s() const = 0;
  // t_s is clamped to [0, duration].
  virtual TruthSample at(double t_s) const = 0;
};

}  // namespace odocal::sim
