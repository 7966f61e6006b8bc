#pragma once
// Dead reckoning: the odometry model (eqs. 1-2) integrated over a whole wheel stream.

#include "odocal/data/log.hpp"

namespace odocal {

// Poses at every wheel sample; pose[0] = start at wheels.t_s[0]. beta = 0 (paper section 2).
PoseStream dead_reckon(const WheelStream& wheels, const OdometryParams& params, const Pose2& start);

}  // namespace odocal
