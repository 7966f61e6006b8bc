#pragma once
// Writes trajectories for users' tools: odocal CSV (t,x,y,heading) and TUM
// ("timestamp tx ty tz qx qy qz qw", planar: z = 0, rotation about +z by the heading).

#include <filesystem>

#include "odocal/data/log.hpp"

namespace odocal {

void write_trajectory_csv(const PoseStream& trajectory, const std::filesystem::path& path);
void write_trajectory_tum(const PoseStream& trajectory, const std::filesystem::path& path);

}  // namespace odocal
