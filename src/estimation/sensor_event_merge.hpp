#pragma once
// The log's sensor streams walked in one time order, for the reference filter. Each stream is
// already sorted, so a four-way merge replaces sorting a materialised event list: no buffer the
// size of the log (whose first touch cost more than the filter itself) and no O(n log n) sort.

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "odocal/data/log.hpp"

namespace odocal {

// At equal times: new IMU input first, then the measurements, then the wheel output (which
// reads the state after everything up to its time).
enum class SensorEventKind { kImu, kGnss, kHeading, kWheel };

struct SensorEvent {
  double t_s;
  SensorEventKind kind;
  std::size_t index;  // into that stream
};

class SensorEventMerge {
 public:
  // Events at or after begin_s. Throws odocal::Error naming the stream if a time base is not
  // strictly increasing (the merge relies on it; the log readers already enforce it).
  SensorEventMerge(const Log& log, double begin_s);

  std::optional<SensorEvent> next();
  std::size_t remaining() const;

 private:
  static constexpr std::size_t kKinds = 4;
  std::array<const std::vector<double>*, kKinds> times_{};
  std::array<std::size_t, kKinds> cursor_{};
};

}  // namespace odocal
