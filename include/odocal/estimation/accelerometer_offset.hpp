#pragma once
// The accelerometer's forward offset, measured where the car stands still and removed from
// imu.csv's ax before the log is used (docs/tyre-model.md, "The accelerometer's forward
// offset"): a mount pitched by p reads g sin p, a force that the tyre model's physical terms
// would take for drive force (0.3 m/s^2 put an urban drive's circumferences 4.5 mm off at a sigma
// of 0.62 mm). Standing, the reading is the offset and the slope where the car stood (with
// altitude, the grade's share is taken out before), so each stop gives one reading, and their
// scatter over the stops says how well their mean is known.

#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/estimation/standstill.hpp"

namespace odocal {

// One stop's mean forward reading.
struct StopReading {
  double forward_mps2{};
  double standing_s{};
};

struct AccelerometerOffset {
  double forward_mps2{};  // the stops' mean reading
  double sigma_mps2{};    // its 1 sigma
  std::size_t stops{};
  double standing_s{};
  bool removed{};  // from ax: only where it stands out of its sigma (accelerometer_offset)
  // 1 sigma of what is left in ax: of the removed offset its sigma; of one left in, itself too.
  double left_sigma_mps2() const {
    return removed ? sigma_mps2 : std::hypot(forward_mps2, sigma_mps2);
  }
};

// What the offset is taken to be uncertain by where no stop measured it, or too few to show
// their slopes' scatter: a mount levelled by eye (0.6 deg), or a stop on a 1 % grade.
inline constexpr double kUnmeasuredForwardOffsetSigmaMps2 = 0.1;
inline constexpr std::size_t kMinStopsForOffset = 3;

// Each standstill's mean ax, its first and last second left out (the body rocks on its springs
// as it stops and pitches as it moves off); stops shorter than that give none.
std::vector<StopReading> standing_forward_readings(const ImuStream& imu,
                                                   const std::vector<Standstill>& standing);

// The mean of the stops' readings, each weighing by its time up to 10 s, and its sigma: their
// scatter about it (from 3 stops on; fewer cannot tell a slope, kUnmeasuredForwardOffsetSigmaMps2),
// and no better than a common slope of 0.05 % under every stop; to be removed where it is beyond
// 3 sigma and 0.02 m/s^2. Nothing without a stop.
std::optional<AccelerometerOffset> accelerometer_offset(const std::vector<StopReading>& stops);

// Whether a measured offset is taken out of ax: beyond 3 of its sigma and 0.02 m/s^2 (0.1 deg of
// pitch). Below, the sigma carries it whole, and a long log is not copied for what its noise hides.
bool forward_offset_stands_out(double forward_mps2, double sigma_mps2);

void remove_accelerometer_offset(ImuStream& imu, double forward_mps2);

// Where no 3 stops measure the offset: the median, over 2 s of driving straight, of the forward
// reading less the wheels' acceleration (at the nominal parameters). That is the offset only as
// far as the wheels' changing slip and, without altitude, the slope let it show; the batch widens
// the unmeasured sigma to it, and removes nothing by it. Nothing without imu.csv or 10 such
// stretches.
std::optional<double> driving_forward_offset(const Log& log, const OdometryParams& nominal);

}  // namespace odocal
