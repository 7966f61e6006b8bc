// The one gravity constant that the simulator, the tyre model, the road grade and the doctor all
// use (a standard gravity for unit conversion lives in io/units.cpp: that one is a definition).
#pragma once

namespace odocal {

inline constexpr double kGravityMps2 = 9.81;

}  // namespace odocal
