#include "odocal/sim/path.hpp"

#include <algorithm>
#include <cmath>

#include "odocal/error.hpp"
#include "odocal/sim/simulation_limits.hpp"

namespace odocal::sim {
namespace {

// Yaw change over the first `ds` of a segment whose curvature starts at k0 and changes by dk/ds.
double yaw_change(double k0, double dk_ds, double ds) { return k0 * ds + 0.5 * dk_ds * ds * ds; }

}  // namespace

Path::Path(std::vector<PathSegment> segments, const Pose2& start, double resolution_m)
    : segments_(std::move(segments)) {
  if (segments_.empty()) throw Error("a path needs at least one segment");
  s_.push_back(0.0);
  pose_.push_back(start);
  signed_distance_m_.push_back(0.0);
  double s = 0.0;
  for (const PathSegment& segment : segments_) {
    if (!(segment.length_m > 0.0) || (segment.direction != 1 && segment.direction != -1)) {
      throw Error("path segments need a positive length and direction +1 or -1");
    }
    if (!(segment.length_m <= kMaxRouteLengthM))
      throw Error("a path segment is longer than the simulator's largest route");
    segment_start_m_.push_back(s);
    const int steps = std::max(1, static_cast<int>(std::ceil(segment.length_m / resolution_m)));
    const double ds = segment.length_m / steps;
    const double dk_ds =
        (segment.curvature_end_1pm - segment.curvature_start_1pm) / segment.length_m;
    for (int i = 0; i < steps; ++i) {
      const double local = i * ds;
      const double k = segment.curvature_start_1pm + dk_ds * local;
      const double d_yaw = segment.direction * yaw_change(k, dk_ds, ds);
      const Pose2& last = pose_.back();
      // Chord of the step along its mean direction: exact for arcs, O(ds^3) for clothoids.
      const double chord = std::abs(d_yaw) > 1e-12 ? 2.0 * std::sin(0.5 * d_yaw) / d_yaw * ds : ds;
      const double travel_yaw = last.z() + 0.5 * d_yaw + (segment.direction < 0 ? M_PI : 0.0);
      pose_.emplace_back(last.x() + chord * std::cos(travel_yaw),
                         last.y() + chord * std::sin(travel_yaw), last.z() + d_yaw);
      s_.push_back(s + (i + 1) * ds);
      signed_distance_m_.push_back(signed_distance_m_.back() + segment.direction * ds);
    }
    s += segment.length_m;
  }
}

PathPoint Path::at(double s_m) const {
  s_m = std::clamp(s_m, 0.0, length_m());
  const std::size_t index =
      std::min<std::size_t>(static_cast<std::size_t>(std::upper_bound(segment_start_m_.begin(),
                                                                      segment_start_m_.end(), s_m) -
                                                     segment_start_m_.begin()) -
                                1,
                            segments_.size() - 1);
  const PathSegment& segment = segments_[index];
  const std::size_t grid = std::min<std::size_t>(
      static_cast<std::size_t>(std::upper_bound(s_.begin(), s_.end(), s_m) - s_.begin()) - 1,
      s_.size() - 2);
  // The grid point may belong to the previous segment when s_m sits exactly on a boundary.
  const std::size_t from = std::max(
      grid, static_cast<std::size_t>(
                std::lower_bound(s_.begin(), s_.end(), segment_start_m_[index]) - s_.begin()));
  const double dk_ds = (segment.curvature_end_1pm - segment.curvature_start_1pm) / segment.length_m;
  const double local_from = s_[from] - segment_start_m_[index];
  const double k_from = segment.curvature_start_1pm + dk_ds * local_from;
  const double ds = s_m - s_[from];
  const double d_yaw = segment.direction * yaw_change(k_from, dk_ds, ds);
  const Pose2& base = pose_[from];
  const double chord = std::abs(d_yaw) > 1e-12 ? 2.0 * std::sin(0.5 * d_yaw) / d_yaw * ds : ds;
  const double travel_yaw = base.z() + 0.5 * d_yaw + (segment.direction < 0 ? M_PI : 0.0);
  PathPoint point;
  point.pose = Pose2(base.x() + chord * std::cos(travel_yaw),
                     base.y() + chord * std::sin(travel_yaw), base.z() + d_yaw);
  point.signed_distance_m = signed_distance_m_[from] + segment.direction * ds;
  point.curvature_1pm = k_from + dk_ds * ds;
  point.direction = segment.direction;
  point.segment = index;
  return point;
}

std::vector<double> Path::direction_changes_m() const {
  std::vector<double> changes;
  for (std::size_t i = 1; i < segments_.size(); ++i) {
    if (segments_[i].direction != segments_[i - 1].direction)
      changes.push_back(segment_start_m_[i]);
  }
  return changes;
}

}  // namespace odocal::sim
