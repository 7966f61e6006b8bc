#pragma once
// Turns a closed track centreline (points, e.g. the TUMFTM racetrack database) into a drivable
// path: clothoid segments between the points, with curvature taken from the points, lightly
// smoothed, and corrected so that one lap closes exactly in heading and position.

#include <Eigen/Core>
#include <vector>

#include "odocal/sim/path.hpp"

namespace odocal::sim {

struct CentrelineRoute {
  std::vector<PathSegment> segments;  // one lap
  Pose2 start;
  double max_deviation_m{};  // largest distance of an input point from the resulting path
};

// Needs at least 8 points, listed in driving order, the last not repeating the first.
// smoothing_points: width of the moving average over vertex curvatures (odd, >= 1).
CentrelineRoute closed_route_from_centreline(const std::vector<Eigen::Vector2d>& points,
                                             int smoothing_points = 3);

}  // namespace odocal::sim
