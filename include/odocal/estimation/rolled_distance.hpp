#pragma once
// The distance the rear wheels rolled up to each wheel sample, at given circumferences, reversing
// counted forward: the path length that altitude fixes and Doppler speeds are placed along.

#include <vector>

#include "odocal/data/log.hpp"

namespace odocal {

// rolled[0] = 0; rolled[k] - rolled[k - 1] = |distance of increment k|.
std::vector<double> rolled_distance_m(const WheelStream& wheels, const OdometryParams& params);

}  // namespace odocal
