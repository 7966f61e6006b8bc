#pragma once
// Encoder ticks cut each wheel's angle to whole ticks, so a wheel's cumulative count lags its
// true angle by up to one tick. The two rear wheels' lags differ by a phase that stays put while
// both turn alike (a straight at a steady speed), and dead reckoning integrates that as a heading
// bias of up to c / (n t) rad: 0.7 deg for 96 ticks of a 1.96 m wheel on a 1.6 m track, which
// on an urban drive is most of the held-out drift left with the true circumferences
// (docs/batch-calibration.md, "Encoder ticks in dead reckoning"). The centred mean of the
// cumulative count over a short window averages the cut over the ticks that pass within it.

#include <vector>

#include "odocal/data/log.hpp"

namespace odocal {

// Half the window that odocal's dead reckoning (`deadreckon`, `validate`) averages a tick
// count over by default.
inline constexpr double kDefaultTickSmoothingS = 0.2;

// The stream with every wheel's cumulative count replaced by a straight line fitted to it over
// +-half_window_s at each sample: its mean where the window is whole, and towards a chain break,
// a gap (wheel_gaps.hpp's default) or the stream's ends, where the window is cut, the line's
// value there. The increment across a break or gap stays as counted. Streams of wheel angles
// or speeds (WheelStream::unit_rear not kTicks) and half_window_s <= 0 return unchanged. Only the
// increments change; a segment's total moves by less than a tick. Taken by value: a caller
// done with its stream moves it in.
WheelStream dequantised_ticks(WheelStream wheels, double half_window_s);

// The stream with only the rear wheels' difference dequantised, their sum left as counted: the
// heading between keyframes without the cut, the distance as it was. The difference is fitted
// as dequantised_ticks fits a count but with a quadratic in place of the line, which follows the
// heading's curvature where a turn begins or ends (a line leaves h^2/6 times the difference's
// second derivative there, which shifted the ideal circuit's circumferences by +0.027 mm at
// +-0.1 s); at +-0.25 s it passes about the cut's noise that the line does at +-0.1 s. For the
// batch's pose graph, whose fixes between keyframes see the cut heading times the antenna's lever
// arm (an error in the regressor that shortens the fitted x, 1.877 m for 1.98 m on a realistic
// urban log of 96 ticks), while a smoothed distance lags the accelerations that the tyre terms read
// as slip (docs/batch-calibration.md, "The encoders' cut in the heading"). The front wheels, angles
// and speeds, and half_window_s <= 0 return unchanged.
WheelStream heading_dequantised_ticks(WheelStream wheels, double half_window_s);

// What heading_dequantised_ticks does to each sample, as the change of its right-minus-left rear
// increment (rev; the right wheel gains half of it, the left loses as much): a FittedWheels of the
// stream and this is that stream without a copy. Empty where it changes nothing.
std::vector<double> heading_tick_change(const WheelStream& wheels, double half_window_s);

}  // namespace odocal
