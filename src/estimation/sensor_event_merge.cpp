#include "sensor_event_merge.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "odocal/error.hpp"

namespace odocal {
namespace {

constexpr std::array<const char*, 4> kStreamNames{"IMU", "GNSS", "heading", "wheel"};

}  // namespace

SensorEventMerge::SensorEventMerge(const Log& log, double begin_s) {
  times_ = {log.imu ? &log.imu->t_s : nullptr, &log.gnss.t_s,
            log.heading ? &log.heading->t_s : nullptr, &log.wheels.t_s};
  for (std::size_t kind = 0; kind < kKinds; ++kind) {
    const std::vector<double>* t_s = times_[kind];
    if (t_s == nullptr) continue;
    const auto out_of_order =
        std::adjacent_find(t_s->begin(), t_s->end(), [](double a, double b) { return !(a < b); });
    if (out_of_order != t_s->end()) {
      throw Error(fmt::format("the {} stream's time is not strictly increasing at sample {}",
                              kStreamNames[kind], out_of_order - t_s->begin() + 1));
    }
    cursor_[kind] = static_cast<std::size_t>(std::lower_bound(t_s->begin(), t_s->end(), begin_s) -
                                             t_s->begin());
  }
}

std::size_t SensorEventMerge::remaining() const {
  std::size_t events = 0;
  for (std::size_t kind = 0; kind < kKinds; ++kind)
    if (times_[kind] != nullptr) events += times_[kind]->size() - cursor_[kind];
  return events;
}

std::optional<SensorEvent> SensorEventMerge::next() {
  std::optional<SensorEvent> earliest;
  for (std::size_t kind = 0; kind < kKinds; ++kind) {
    const std::vector<double>* t_s = times_[kind];
    if (t_s == nullptr || cursor_[kind] == t_s->size()) continue;
    const double t = (*t_s)[cursor_[kind]];
    // Strictly earlier only: on a tie the lower kind, visited first, keeps precedence.
    if (!earliest || t < earliest->t_s)
      earliest = SensorEvent{t, static_cast<SensorEventKind>(kind), cursor_[kind]};
  }
  if (earliest) ++cursor_[static_cast<std::size_t>(earliest->kind)];
  return earliest;
}

}  // namespace odocal
