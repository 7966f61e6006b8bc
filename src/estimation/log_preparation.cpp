#include "odocal/estimation/log_preparation.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "odocal/error.hpp"
#include "odocal/estimation/log_window.hpp"

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

std::optional<Log> prepare_log(const Log& log, const CalibrationOptions& options,
                               LogPreparation& done, bool need_gnss_span) {
  std::optional<Log> prepared;
  const auto edit = [&]() -> Log& {
    if (!prepared) prepared = log;
    return *prepared;
  };
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
      prepared = crop_log(log, from, to);
    }
  }
  const OdometryParams nominal = log.vehicle.nominal_params();
  done.standstills = find_standstills(prepared ? *prepared : log, nominal, options.standstill);
  const bool rate_sensor = log.wheels.unit_rear == WheelUnit::kRadiansPerSecond ||
                           log.wheels.unit_rear == WheelUnit::kMetresPerSecond;
  if (options.remove_wheel_rate_bias && rate_sensor && !done.standstills.empty()) {
    done.wheel_rate_bias = wheel_rate_bias((prepared ? *prepared : log).wheels, done.standstills);
    remove_wheel_rate_bias(edit().wheels, *done.wheel_rate_bias);
  }
  if (options.start_at_first_motion) {
    const Log& current = prepared ? *prepared : log;
    const std::optional<double> moving =
        first_motion_s(current.wheels, nominal, options.coverage.moving_speed_mps);
    // Only a real standing start is cut (a second or two is harmless), keeping a little of it
    // for the filters to settle.
    constexpr double kMinStandingS = 5.0, kLeadS = 1.0;
    if (moving && *moving - current.wheels.t_s.front() > kMinStandingS) {
      done.started_at_s = *moving - kLeadS;
      prepared = crop_log(current, *done.started_at_s, current.wheels.t_s.back());
    }
  }
  if (options.use_gnss_altitude) {
    const Log& current = prepared ? *prepared : log;
    if (const auto profile = grade_from_gnss_altitude(current, nominal, options.grade_window_m)) {
      done.typical_max_grade = profile->typical_max_grade();
      done.length_excess = profile->length_excess();
      done.grade_scale_variance = profile->scale_variance();
      project_to_horizontal(edit(), *profile);
    }
  }
  const WheelStream& wheels = prepared ? prepared->wheels : log.wheels;
  const double max_gap_s =
      options.max_wheel_gap_s > 0.0 ? options.max_wheel_gap_s : default_max_wheel_gap_s(wheels);
  done.wheel_gaps = find_wheel_gaps(wheels, max_gap_s);
  if (!done.wheel_gaps.empty()) break_chain_at_gaps(edit().wheels, done.wheel_gaps);
  return prepared;
}

}  // namespace odocal
