#pragma once
// Length of the polyline through a sequence of poses (metres).

#include <vector>

#include "odocal/model/odometry_model.hpp"

namespace odocal {

inline double path_length_m(const std::vector<Pose2>& poses) {
  double length_m = 0.0;
  for (std::size_t k = 1; k < poses.size(); ++k)
    length_m += (poses[k].head<2>() - poses[k - 1].head<2>()).norm();
  return length_m;
}

}  // namespace odocal
