#pragma once
// The planar motion of a vehicle on hills along its road (Terrain in scenario.hpp): the wheels
// roll the 3-D distance, the body pitches with the grade so that the accelerometer feels gravity
// along the slope and the gyro turns a little less, and the road's altitude is known for GNSS.

#include <memory>
#include <vector>

#include "hills.hpp"
#include "odocal/sim/motion_truth.hpp"
#include "odocal/sim/scenario.hpp"

namespace odocal::sim {

class GradedMotion : public MotionTruth {
 public:
  // `lap_length_m`: horizontal length of one lap (the wavelength is rounded to divide it).
  GradedMotion(std::unique_ptr<MotionTruth> flat, const Terrain& terrain, double lap_length_m);

  double duration_s() const override { return flat_->duration_s(); }
  TruthSample at(double t_s) const override;

 private:
  double interpolate(const std::vector<double>& values, double t_s) const;
  double grade(double s_m) const { return hills_.grade(s_m); }

  std::unique_ptr<MotionTruth> flat_;
  Hills hills_;
  // On a fine time grid: horizontal distance driven, and what the slope adds to each wheel angle.
  double grid_step_s_{};
  std::vector<double> distance_m_, extra_angle_rl_rad_, extra_angle_rr_rad_;
};

}  // namespace odocal::sim
