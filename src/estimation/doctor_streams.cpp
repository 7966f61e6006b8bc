// The doctor's checks of the streams themselves: the clocks' spans, wheel gaps, repeated GNSS
// positions and a missing altitude.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "doctor.hpp"

namespace odocal::detail {

bool Doctor::check_spans() {
  const auto& wheels = facts_.wheels;
  const auto& gnss = facts_.gnss;
  const double wheels_s = wheels.last_s - wheels.first_s;
  const double gnss_s = gnss.last_s - gnss.first_s;
  const double ratio = gnss_s / wheels_s;
  for (const double factor : {10.0, 100.0, 1000.0, 1e6, 1e9, 60.0, 3600.0}) {
    for (const double r : {factor, 1.0 / factor}) {
      if (std::abs(ratio / r - 1.0) < 0.05) {
        add("time.scale", FindingSeverity::kBlocking,
            "the GNSS and wheel clocks run at different rates",
            fmt::format("gnss.csv spans {:.6g} s, wheels.csv {:.6g} s (x{:.4g})", gnss_s, wheels_s,
                        ratio),
            "a time column in the wrong unit (ms read as s, or s read as ms, ...)",
            fmt::format("scale the time of gnss.csv by {:g} (import map: time.unit)", 1.0 / r));
        return false;
      }
    }
  }
  const double overlap_s =
      std::min(wheels.last_s, gnss.last_s) - std::max(wheels.first_s, gnss.first_s);
  if (signals_.size() == 0 && overlap_s > 0.0) {
    add("time.short", FindingSeverity::kNote, "too short to compare the streams",
        fmt::format("wheels and GNSS share {:.1f} s", overlap_s), "", "");
    return false;
  }
  if (signals_.size() == 0) {
    add("time.span", FindingSeverity::kBlocking, "wheels and GNSS share no time",
        fmt::format("wheels {:.3f} to {:.3f} s, GNSS {:.3f} to {:.3f} s", wheels.first_s,
                    wheels.last_s, gnss.first_s, gnss.last_s),
        "the two loggers' clocks are unrelated (different epochs)",
        "give both streams one clock (import map: time.offset_s)");
    return false;
  }
  const double shared = seconds(signals_.size());
  if (shared < 0.9 * std::min(wheels_s, gnss_s) - 2.0 ||
      shared < 0.5 * std::max(wheels_s, gnss_s)) {
    add("time.span", FindingSeverity::kWarning, "the streams cover different spans",
        fmt::format("wheels {:.1f} s, GNSS {:.1f} s, both {:.1f} s", wheels_s, gnss_s, shared),
        "a logger started late or stopped early, or its clock is offset",
        "calibration uses the shared span only; check the time columns if it should be longer");
  }
  check_optional_span("imu.csv", facts_.imu);
  check_optional_span("heading.csv", facts_.heading);
  return true;
}

void Doctor::check_optional_span(const char* file, const StreamSpan& span) {
  if (span.samples == 0) return;
  const double wheels_from = facts_.wheels.first_s, wheels_to = facts_.wheels.last_s;
  const double covered = std::min(wheels_to, span.last_s) - std::max(wheels_from, span.first_s);
  const double wheels_s = wheels_to - wheels_from;
  if (covered < 0.9 * wheels_s - 2.0) {
    add("time.span", FindingSeverity::kWarning, "the streams cover different spans",
        fmt::format("{} covers {:.1f} s of the wheels' {:.1f} s ({:.3f} to {:.3f} s)", file,
                    std::max(0.0, covered), wheels_s, span.first_s, span.last_s),
        "a logger started late or stopped early, or its clock is offset",
        fmt::format("the reference has no {} for the rest; check its time column", file));
  }
}

void Doctor::check_gnss_repeats() {
  const std::size_t repeated = facts_.gnss_repeated, first = facts_.gnss_first_repeated_row;
  const double share =
      facts_.gnss.samples > 1 ? double(repeated) / double(facts_.gnss.samples - 1) : 0.0;
  // Standing still repeats a fix legitimately; a quarter of all rows is more than that.
  if (share > 0.25) {
    add("gnss.repeated", FindingSeverity::kBlocking, "GNSS fixes are repeated on many rows",
        fmt::format("{:.0f} % of rows repeat the previous position (first at row {})", 100 * share,
                    first + 1),
        "the GNSS was logged faster than the receiver makes fixes: each fix counts several times "
        "and the sigma is too small",
        "keep only the rows where the fix changes (or log at the receiver's rate)");
  }
}

void Doctor::check_gaps() {
  const auto& gaps = facts_.wheel_gaps;
  if (!gaps.empty()) {
    const auto longest = std::max_element(
        gaps.begin(), gaps.end(),
        [](const WheelGap& a, const WheelGap& b) { return a.duration_s < b.duration_s; });
    add("wheels.gaps", FindingSeverity::kWarning,
        fmt::format("{} gap(s) in the wheel stream", gaps.size()),
        fmt::format("longest {:.2f} s at {:.1f} s", longest->duration_s, longest->start_s),
        "dropped packets or a logger pause",
        "none needed: the odometry chain restarts at each gap");
  }
  if (facts_.gnss_gap) {
    const auto [longest, typical] = *facts_.gnss_gap;
    add("gnss.gaps", FindingSeverity::kNote, "the GNSS has gaps",
        fmt::format("longest {:.1f} s (fixes every {:.3g} s)", longest, typical),
        "an outage (tunnel, garage) or dropped messages", "none needed");
  }
}

void Doctor::check_altitude() {
  if (!facts_.gnss_altitude) {
    add("gnss.altitude", FindingSeverity::kNote, "the GNSS has no altitude",
        "gnss.csv has no alt column",
        "on hills the 3-D path is longer than the planar one and biases the circumferences",
        "log the altitude (gnss alt column) if the drive is not flat");
  }
}

}  // namespace odocal::detail
