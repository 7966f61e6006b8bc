#include "odocal/estimation/dead_reckoning.hpp"

namespace odocal {

PoseStream dead_reckon(const WheelStream& wheels, const OdometryParams& params,
                       const Pose2& start) {
  PoseStream trajectory;
  trajectory.t_s = wheels.t_s;
  trajectory.pose.resize(wheels.size());
  if (wheels.size() == 0) return trajectory;
  trajectory.pose[0] = start;
  for (std::size_t k = 1; k < wheels.size(); ++k) {
    trajectory.pose[k] = predict_pose(trajectory.pose[k - 1], wheels.increment(k), params);
  }
  return trajectory;
}

}  // namespace odocal
