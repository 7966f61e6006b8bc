#include "odocal/estimation/log_preparation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "odocal/data/stream_columns.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/log_window.hpp"
#include "odocal/estimation/prepared_blocks.hpp"

namespace odocal {

double LogPreparation::standing_s() const {
  double total = 0.0;
  for (const Standstill& still : standstills) total += still.end_s - still.start_s;
  return total;
}

std::string LogPreparation::describe() const {
  std::string text;
  if (common_span_s) {
    text += fmt::format(
        "; {:.1f} s of wheel data outside the GNSS span cut off (used {:.1f} to "
        "{:.1f} s)",
        cut_without_gnss_s, common_span_s->first, common_span_s->second);
  }
  if (!standstills.empty()) {
    text += fmt::format("; standing {:.1f} s in {} period(s)", standing_s(), standstills.size());
  }
  if (wheel_rate_bias) {
    constexpr double kDegPerRev = 360.0;
    text += fmt::format("; wheel rate bias removed: RL {:+.3f} deg/s, RR {:+.3f} deg/s",
                        kDegPerRev * wheel_rate_bias->rl_rev_per_s,
                        kDegPerRev * wheel_rate_bias->rr_rev_per_s);
    if (wheel_rate_bias_per_block.size() > 1) {
      const auto range = [&](double WheelRateBias::*wheel) {
        const auto [low, high] = std::minmax_element(
            wheel_rate_bias_per_block.begin(), wheel_rate_bias_per_block.end(),
            [&](const BlockBias& a, const BlockBias& b) { return a.bias.*wheel < b.bias.*wheel; });
        return std::make_pair(kDegPerRev * low->bias.*wheel, kDegPerRev * high->bias.*wheel);
      };
      const auto rl = range(&WheelRateBias::rl_rev_per_s);
      const auto rr = range(&WheelRateBias::rr_rev_per_s);
      text += fmt::format(
          " (the standing-time mean of {} blocks' own: RL {:+.3f} to {:+.3f}, RR {:+.3f} to "
          "{:+.3f})",
          wheel_rate_bias_per_block.size(), rl.first, rl.second, rr.first, rr.second);
    }
  }
  if (const auto& drive = drive_forward_offset) {
    text += fmt::format(
        "; accelerometer's forward offset {} over {:.0f} s of driving (too few stops): {:+.3f} "
        "m/s^2 (1-sigma {:.3f})",
        drive->removed ? "removed" : "within its noise, left in", drive->duration_s,
        drive->forward_mps2, drive->sigma_mps2);
  } else if (const auto& offset = accelerometer_offset) {
    text += fmt::format(
        "; accelerometer's forward offset {}: {:+.3f} m/s^2 (1-sigma {:.3f}) at {} stop(s)",
        offset->removed ? "removed" : "within its noise, left in", offset->forward_mps2,
        offset->sigma_mps2, offset->stops);
  }
  if (unevenly_removed_forward_mps2 > 0.0) {
    text += fmt::format(
        " (the log's blocks each removed the estimate of their time: {:.3f} m/s^2 RMS from the "
        "last)",
        unevenly_removed_forward_mps2);
  }
  if (driving_forward_offset_mps2) {
    text += fmt::format(
        "; the accelerometer reads {:+.3f} m/s^2 forward beyond the wheels' acceleration while "
        "driving straight (too few stops to measure its offset at: not removed)",
        *driving_forward_offset_mps2);
  }
  if (started_at_s) text += fmt::format("; used from {:.1f} s (first motion)", *started_at_s);
  if (typical_max_grade) {
    text += fmt::format(
        "; grade from GNSS altitude within {:.1f} % on 95 % of the road, the 3-D path {:.3f} % "
        "longer than the 2-D one (projected)",
        100.0 * *typical_max_grade, 100.0 * length_excess);
  }
  if (!wheel_gaps.empty()) {
    const auto longest = std::max_element(
        wheel_gaps.begin(), wheel_gaps.end(),
        [](const WheelGap& a, const WheelGap& b) { return a.duration_s < b.duration_s; });
    text += fmt::format(
        "; {} gap(s) in the wheel stream (longest {:.2f} s at {:.1f} s): the odometry chain "
        "restarts there",
        wheel_gaps.size(), longest->duration_s, longest->start_s);
  }
  if (text.starts_with("; ")) text.erase(0, 2);
  return text;
}

namespace {

// The log prepared block by block; `changed`: whether preparing changed anything.
Log prepared_blocks(const Log& whole, const CalibrationOptions& options, LogPreparation& done,
                    std::optional<double> forward_offset_mps2, bool& changed) {
  InMemoryLogSource source(whole);
  BlockPreparation blocks(source, options, done, forward_offset_mps2);
  Log prepared;
  prepared.source = whole.source;
  prepared.vehicle = whole.vehicle;
  const auto append = [&](const Log& core) {
    append_stream(prepared.wheels, core.wheels);
    append_stream(prepared.gnss, core.gnss);
    const auto append_optional = [](auto& to, const auto& from) {
      if (!from) return;
      if (!to) to.emplace();
      append_stream(*to, *from);
    };
    append_optional(prepared.imu, core.imu);
    append_optional(prepared.heading, core.heading);
    append_optional(prepared.truth, core.truth);
  };
  // Blocks that preparing left as they were are copied only once a later block changes: a log
  // that nothing changes is not copied at all.
  std::optional<double> unchanged_from;
  while (const std::optional<PreparedBlock> block = blocks.next()) {
    if (!blocks.changed()) {
      if (!unchanged_from) unchanged_from = block->core_from_s;
      continue;
    }
    if (unchanged_from) {
      Log before = slice_log(whole, *unchanged_from, std::nextafter(block->core_from_s, -INFINITY));
      start_wheel_chain(before.wheels);
      append(before);
      unchanged_from.reset();
    }
    append(core_log(*block));
  }
  changed = blocks.changed();
  return prepared;
}

}  // namespace

std::optional<Log> prepare_log(const Log& log, const CalibrationOptions& options,
                               LogPreparation& done, bool need_gnss_span) {
  std::optional<Log> span;
  if (need_gnss_span) {
    const double wheel_from = log.wheels.t_s.front(), wheel_to = log.wheels.t_s.back();
    const double from = std::max(wheel_from, log.gnss.t_s.front());
    const double to = std::min(wheel_to, log.gnss.t_s.back());
    constexpr double kMinCommonS = 2.0;
    if (!(to - from >= kMinCommonS)) {
      throw InsufficientDataError(fmt::format(
          "wheels ({:.3f} to {:.3f} s) and GNSS ({:.3f} to {:.3f} s) share {:.3f} s of time: "
          "the streams' clocks or time units disagree",
          wheel_from, wheel_to, log.gnss.t_s.front(), log.gnss.t_s.back(),
          std::max(0.0, to - from)));
    }
    // A few GNSS periods beyond either end is the normal sampling offset.
    const double tolerance_s =
        std::max(1.0, 5.0 * (log.gnss.t_s.back() - log.gnss.t_s.front()) /
                          static_cast<double>(std::max<std::size_t>(1, log.gnss.size() - 1)));
    if (from - wheel_from > tolerance_s || wheel_to - to > tolerance_s) {
      done.common_span_s = {from, to};
      done.cut_without_gnss_s = (from - wheel_from) + (wheel_to - to);
      span = crop_log(log, from, to);
    }
  }
  const Log& whole = span ? *span : log;
  const LogPreparation before = done;
  bool changed = false;
  Log prepared = prepared_blocks(whole, options, done, std::nullopt, changed);
  if (const std::optional<double> offset_mps2 = done.forward_offset_for_every_block()) {
    // A long log's early blocks removed the running estimate of their time: prepared again, with
    // what the whole log measured removed from every block (the first copy freed before the
    // second is built).
    prepared = Log{};
    done = before;
    prepared = prepared_blocks(whole, options, done, offset_mps2, changed);
  }
  if (!changed) return span;
  if (prepared.wheels.size() < 2 || prepared.gnss.t_s.empty()) {
    require_window_holds(prepared.wheels.size(), prepared.gnss.size(),
                         done.started_at_s.value_or(whole.wheels.t_s.front()),
                         whole.wheels.t_s.back(), whole.wheels.t_s.front(),
                         whole.wheels.t_s.back());
  }
  return prepared;
}

}  // namespace odocal
