#pragma once
// The track the wheels roll on, against vehicle.yaml's: how many times faster the wheels' yaw
// rate (computed with the stated track and circumferences) turns than the gyro's, at rest speed.
// The load transfer in a turn changes the wheels' radii by a share that grows with the speed
// squared, whatever the lateral acceleration (at 10 m/s on a sedan about a tenth of the turn's
// speed difference), so the scale is fitted as a + b v^2 and `a` is taken; a gyro bias and a
// left/right circumference difference are fitted beside it (a constant and v). Only from a log
// that turns below 10 m/s for 20 s or more: from fast turns alone the extrapolation to rest
// speed carries the driven wheels' slip.

#include <vector>

#include "diagnosis_signals.hpp"

namespace odocal::detail {

struct WheelTurnScale {
  double at_rest{};       // a: NaN where the log cannot tell it
  double sigma{};         // its 1-sigma from the fit's scatter
  std::size_t turning{};  // samples turning faster than 0.1 rad/s by the gyro
};

// Over the samples where `use` holds (moving); needs the gyro.
WheelTurnScale wheel_turn_scale(const DiagnosisSignals& signals, const std::vector<bool>& use);

}  // namespace odocal::detail
