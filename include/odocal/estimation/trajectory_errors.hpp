#pragma once
// How far a trajectory is from a reference: the mean/max position and heading errors the paper
// reports (Table 1, Figs. 6, 9, 10), plus final drift.

#include <string>
#include <vector>

#include "odocal/data/log.hpp"

namespace odocal {

// Reference positions and (optionally) headings, each on its own time base.
struct ReferencePath {
  std::string name;  // for reports, e.g. "truth.csv"
  std::vector<double> position_t_s, x_m, y_m;
  std::vector<double> heading_t_s, heading_rad;  // empty: no heading reference
};

ReferencePath reference_from_poses(const PoseStream& poses, std::string name);
// GNSS positions; headings from `heading` when given.
ReferencePath reference_from_gnss(const GnssStream& gnss, const HeadingStream* heading);

struct TrajectoryErrors {
  std::size_t position_samples{};
  double mean_position_m{};
  double max_position_m{};
  double final_position_m{};      // at the last reference sample inside the trajectory
  std::size_t heading_samples{};  // 0 when the reference has no heading
  double mean_heading_rad{};
  double max_heading_rad{};
  double distance_m{};  // travelled along the trajectory
  double final_drift_percent{};
};

// Compares at every reference sample inside the trajectory's time span. Throws Error when no
// reference position falls inside it.
TrajectoryErrors trajectory_errors(const PoseStream& trajectory, const ReferencePath& reference);

// The same over a trajectory that comes in pieces (a long log dead-reckoned a block at a time):
// each piece starts with the last pose of the one before, and is compared at the reference
// samples after that pose, so that every sample counts once.
class TrajectoryErrorSum {
 public:
  void add(const PoseStream& piece, const ReferencePath& reference);
  // Throws Error (naming `reference_name`) when no reference position fell inside.
  TrajectoryErrors result(const std::string& reference_name) const;

 private:
  TrajectoryErrors sums_;
  double position_sum_m_{}, heading_sum_rad_{};
  bool first_piece_ = true;
};

}  // namespace odocal
