#pragma once
// A driver's speed along a path: as fast as the speed limit and a lateral-acceleration bound in
// corners allow, reached with bounded acceleration and braking (optionally sharing the grip with
// the turn and limited by the engine's power), with full stops where the driving
// direction changes and at requested stop points. Piecewise constant acceleration between grid
// points, so position and speed at any time have closed forms.

#include <vector>

#include "odocal/sim/path.hpp"

namespace odocal::sim {

struct Stop {
  double at_m{};     // unsigned distance along the path
  double dwell_s{};  // standing time
};

struct DriverLimits {
  double max_speed_mps = 50.0;
  double max_reverse_speed_mps = 2.0;
  double max_lateral_acc_mps2 = 6.0;
  double max_acc_mps2 = 3.0;
  double max_brake_mps2 = 6.0;
  // A driver who shares the grip between turning and speeding up or slowing down (a g-g
  // diagram): a_x <= max_acc (or max_brake) * sqrt(1 - (a_y / max_lateral_acc)^2), a twentieth
  // of it kept so that a bend driven at its cap can be left. false: each bound on its own.
  bool friction_ellipse = false;
  double max_power_wpkg = 0.0;  // engine power per kg of car: a_x <= P / v (0: no limit)
  double start_dwell_s = 1.0;   // standing still before moving off (and after arriving)
};

struct MotionState {
  double s_m{};        // unsigned distance along the path
  double speed_mps{};  // >= 0, along the direction of travel
  double acc_mps2{};   // d(speed)/dt
};

class SpeedProfile {
 public:
  // segment_speed_scale: per path segment, scales the speed caps (empty: all 1).
  SpeedProfile(const Path& path, const DriverLimits& limits, const std::vector<Stop>& stops,
               const std::vector<double>& segment_speed_scale = {}, double grid_m = 1.0);
  double duration_s() const { return depart_s_.back(); }
  MotionState at(double t_s) const;

 private:
  std::vector<double> s_m_;
  std::vector<double> speed_mps_;
  std::vector<double> arrive_s_;  // time of reaching grid point i
  std::vector<double> depart_s_;  // time of leaving it (after any dwell)
};

}  // namespace odocal::sim
