#pragma once
// Dead reckoning: the odometry model (eqs. 1-2) integrated over a whole wheel stream.

#include <cstdint>
#include <functional>
#include <vector>

#include "odocal/data/log.hpp"

namespace odocal {

// Poses at every wheel sample; pose[0] = start at wheels.t_s[0]. beta = 0 (paper section 2).
PoseStream dead_reckon(const WheelStream& wheels, const OdometryParams& params, const Pose2& start);

// The same, restarting where the odometry chain breaks (a wheel gap, WheelStream::breaks_at):
// the pose there is restart(t_s, the pose dead reckoning carried to the break).
PoseStream dead_reckon(const WheelStream& wheels, const OdometryParams& params, const Pose2& start,
                       const std::function<Pose2(double, const Pose2&)>& restart);

// The same into a caller's buffer: path[i] follows from path[i - 1] and the increment of wheel
// sample first_sample + i, for every i in [begin, end) (default: every i >= 1); path[0] is the
// start and stays as given.
void dead_reckon_into(const WheelStream& wheels, std::size_t first_sample,
                      const OdometryParams& params, std::vector<Pose2>& path, std::size_t begin = 1,
                      std::size_t end = SIZE_MAX);

}  // namespace odocal
