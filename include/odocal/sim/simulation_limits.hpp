#pragma once
// How large a simulated drive may be: any real log is far inside these, and beyond them a run
// would take hours and more memory than the machine has (a typo such as stop_s: 1e9). A scenario
// past a limit is an InputError saying which limit and by how much.

#include "odocal/sim/scenario.hpp"

namespace odocal::sim {

inline constexpr double kMaxRouteLengthM = 5e6;  // 5000 km, all laps
inline constexpr double kMaxDriveDurationS = 100 * 3600.0;
inline constexpr double kMaxSamplesPerStream = 1e7;  // 27 h at 100 Hz

// Route length (finite, within kMaxRouteLengthM) before anything is built.
void check_route_size(const Scenario& scenario);

// Duration and samples per sensor stream once the speed profile is known.
void check_drive_size(const Scenario& scenario, double duration_s);

}  // namespace odocal::sim
