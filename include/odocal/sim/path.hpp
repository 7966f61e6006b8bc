#pragma once
// The path a simulated vehicle drives: segments of linearly varying curvature (straights, arcs,
// clothoids), each driven forwards or in reverse. Curvature is of the vehicle's motion:
// d(yaw)/d(signed distance), so a reversing segment with positive curvature yaws the vehicle
// left as it backs up.

#include <vector>

#include "odocal/model/odometry_model.hpp"

namespace odocal::sim {

struct PathSegment {
  double length_m{};
  double curvature_start_1pm{};
  double curvature_end_1pm{};
  int direction{1};  // +1 forwards, -1 reversing
};

// State of the reference point at path parameter s (unsigned distance along the path).
struct PathPoint {
  Pose2 pose;                // x, y, yaw (continuous, unwrapped)
  double signed_distance_m;  // D: forwards minus reversed distance from the start
  double curvature_1pm;
  int direction;
  std::size_t segment;  // index into segments()
};

class Path {
 public:
  // Integrates the segments from `start` on a grid of at most `resolution_m`.
  Path(std::vector<PathSegment> segments, const Pose2& start, double resolution_m = 0.25);

  double length_m() const { return s_.back(); }
  const std::vector<PathSegment>& segments() const { return segments_; }
  // s is clamped to [0, length]. Yaw, D and curvature are exact; x, y exact at grid points and
  // interpolated along the local arc between them.
  PathPoint at(double s_m) const;
  // Unsigned distances where the driving direction changes (the vehicle must stop there).
  std::vector<double> direction_changes_m() const;

 private:
  std::vector<PathSegment> segments_;
  std::vector<double> segment_start_m_;
  std::vector<double> s_;  // grid
  std::vector<Pose2> pose_;
  std::vector<double> signed_distance_m_;
};

}  // namespace odocal::sim
