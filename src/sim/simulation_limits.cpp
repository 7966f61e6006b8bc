#include "odocal/sim/simulation_limits.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "odocal/error.hpp"

namespace odocal::sim {
namespace {

InputError too_large(const std::string& field, const std::string& problem) {
  return InputError({"scenario", 0, field}, problem);
}

}  // namespace

void check_route_size(const Scenario& scenario) {
  double lap_m = 0.0;
  for (const RouteSegment& segment : scenario.route.segments) {
    if (!std::isfinite(segment.geometry.length_m) || !std::isfinite(segment.stop_dwell_s))
      throw too_large("route", "a segment's length or stop is not finite");
    lap_m += segment.geometry.length_m;
  }
  const double total_m = lap_m * scenario.route.repeat * scenario.route.laps;
  if (!(total_m <= kMaxRouteLengthM)) {
    throw too_large("route",
                    fmt::format("the drive would be {:.0f} km long ({} laps of {:.1f} km); "
                                "the simulator makes at most {:.0f} km",
                                total_m / 1e3, scenario.route.laps,
                                lap_m * scenario.route.repeat / 1e3, kMaxRouteLengthM / 1e3));
  }
}

void check_drive_size(const Scenario& scenario, double duration_s) {
  if (!(duration_s <= kMaxDriveDurationS)) {
    throw too_large("route", fmt::format("the drive would last {:.1f} h (stops included); the "
                                         "simulator makes at most {:.0f} h",
                                         duration_s / 3600.0, kMaxDriveDurationS / 3600.0));
  }
  const double fastest_hz = std::max({scenario.wheels.rate_hz, scenario.gnss.rate_hz,
                                      scenario.imu.rate_hz, scenario.heading.rate_hz});
  if (!(duration_s * fastest_hz <= kMaxSamplesPerStream)) {
    throw too_large("sensors", fmt::format("{:.1f} h at {:g} Hz would be {:.3g} samples in one "
                                           "stream; the simulator writes at most {:.0g}",
                                           duration_s / 3600.0, fastest_hz, duration_s * fastest_hz,
                                           kMaxSamplesPerStream));
  }
}

}  // namespace odocal::sim
