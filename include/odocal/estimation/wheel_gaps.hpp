#pragma once
// Gaps in the wheel stream. Integrating across one as if the vehicle had driven straight (or at
// the last sampled speed) invents motion: a 1.6 s gap of angular-rate wheel sensors once became
// a 126 deg heading jump. Instead the odometry chain breaks there: every estimator restarts or
// bridges it with the reference, and the summary lists the gaps.

#include <vector>

#include "odocal/data/log.hpp"

namespace odocal {

struct WheelGap {
  std::size_t sample{};  // the first sample after the gap: its increment spans the gap
  double start_s{};      // time of the sample before the gap
  double duration_s{};
};

// The median interval between consecutive samples; 0 for fewer than two.
double median_sample_period_s(const WheelStream& wheels);

// Five times the median sample period: a dropped sample or two is no gap, a second is.
inline constexpr double kMaxWheelGapPeriods = 5.0;
inline double default_max_wheel_gap_s(const WheelStream& wheels) {
  return kMaxWheelGapPeriods * median_sample_period_s(wheels);
}

// Every interval between consecutive samples longer than max_gap_s.
std::vector<WheelGap> find_wheel_gaps(const WheelStream& wheels, double max_gap_s);

// Marks the gaps as chain breaks (WheelStream::chain_break) and zeroes their increments.
void break_chain_at_gaps(WheelStream& wheels, const std::vector<WheelGap>& gaps);

}  // namespace odocal
