#pragma once
// A wheel stream as a fit reads it: the stream's own samples, with each sample's right-minus-left
// rear increment changed by a given amount (half on each wheel, their sum as counted). The batch
// fits the log's stream with its heading smoothed this way (tick_dequantisation.hpp's
// heading_tick_change) without a second copy of its times and wheels, 79 MiB on a 10-hour drive.

#include <span>
#include <vector>

#include "odocal/data/log.hpp"

namespace odocal {

class FittedWheels {
 public:
  // `difference_change`: one value per sample (rev), or empty for the stream as it is. Both are
  // referred to, not copied. Implicit, so that a stream is read as itself.
  FittedWheels(const WheelStream& wheels, std::span<const double> difference_change = {})
      : stream(wheels),
        t_s(wheels.t_s),
        grade(wheels.grade),
        drive_force_n(wheels.drive_force_n),
        change_(difference_change) {}

  const WheelStream& stream;
  const std::vector<double>& t_s;
  const std::vector<float>& grade;
  const std::vector<double>& drive_force_n;

  std::size_t size() const { return t_s.size(); }
  bool breaks_at(std::size_t k) const { return stream.breaks_at(k); }
  WheelIncrement increment(std::size_t k) const {
    WheelIncrement n = stream.increment(k);
    if (!change_.empty()) {
      const double half = 0.5 * change_[k];
      n.rev_rl -= half;
      n.rev_rr += half;
    }
    return n;
  }

 private:
  std::span<const double> change_;
};

}  // namespace odocal
