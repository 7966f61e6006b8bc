#include "odocal/estimation/dead_reckoning.hpp"

#include <algorithm>

#include "hot_loop.hpp"
#include "odocal/model/stepwise_cos_sin.hpp"

namespace odocal {

PoseStream dead_reckon(const WheelStream& wheels, const OdometryParams& params,
                       const Pose2& start) {
  PoseStream trajectory;
  trajectory.t_s = wheels.t_s;
  trajectory.pose.resize(wheels.size());
  if (wheels.size() == 0) return trajectory;
  trajectory.pose[0] = start;
  dead_reckon_into(wheels, 0, params, trajectory.pose);
  return trajectory;
}

PoseStream dead_reckon(const WheelStream& wheels, const OdometryParams& params, const Pose2& start,
                       const std::function<Pose2(double, const Pose2&)>& restart) {
  PoseStream trajectory;
  trajectory.t_s = wheels.t_s;
  trajectory.pose.resize(wheels.size());
  if (wheels.size() == 0) return trajectory;
  trajectory.pose[0] = start;
  std::size_t begin = 1;
  for (std::size_t k = 1; k <= wheels.size(); ++k) {
    if (k < wheels.size() && !wheels.breaks_at(k)) continue;
    dead_reckon_into(wheels, 0, params, trajectory.pose, begin, k);
    if (k == wheels.size()) break;
    trajectory.pose[k] = restart(wheels.t_s[k], trajectory.pose[k - 1]);
    begin = k + 1;
  }
  return trajectory;
}

ODOCAL_HOT_LOOP void dead_reckon_into(const WheelStream& wheels, std::size_t first_sample,
                                      const OdometryParams& params, std::vector<Pose2>& path,
                                      std::size_t begin, std::size_t end) {
  StepwiseCosSin course_cos_sin;
  for (std::size_t i = begin; i < std::min(end, path.size()); ++i) {
    const WheelIncrement increment = wheels.increment(first_sample + i);
    const BodyIncrement step = body_increment(increment, params);
    const CosSin course =
        course_cos_sin(path[i - 1].z() + 0.5 * step.yaw_rad + wheels.side_slip(first_sample + i));
    path[i] = predict_pose_on_course(path[i - 1], increment, step, course, params);
  }
}

}  // namespace odocal
