#include "odocal/estimation/standstill.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/median.hpp"

namespace odocal {

OptionTable<StandstillOptions> StandstillOptions::fields() {
  using O = StandstillOptions;
  static const std::array<OptionField<O>, 4> kFields{{
      {"max_speed_mps", "m/s", 0.0, 1.0, "standing: wheel speed below this", &O::max_speed_mps},
      {"min_duration_s", "s", 0.0, 600.0, "for at least this long", &O::min_duration_s},
      {"max_gnss_speed_mps", "m/s", 0.0, 10.0, "and GNSS Doppler speed below this (if logged)",
       &O::max_gnss_speed_mps},
      {"max_turn_rate_radps", "rad/s", 0.0, 10.0, "and the gyro below this (if logged)",
       &O::max_turn_rate_radps},
  }};
  return kFields;
}

std::string StandstillOptions::validate() const { return check_option_ranges(fields(), *this); }

std::vector<Standstill> find_standstills(const Log& log, const OdometryParams& nominal,
                                         const StandstillOptions& options) {
  const WheelStream& wheels = log.wheels;
  const auto still = [&](std::size_t k) {
    const double dt = wheels.t_s[k] - wheels.t_s[k - 1];
    if (std::abs(body_increment(wheels.increment(k), nominal).distance_m) >
        options.max_speed_mps * dt) {
      return false;
    }
    return true;
  };
  // A stretch the wheels call standing, confirmed by the mean GNSS speed and the mean gyro rate
  // over it (single samples are too noisy).
  const auto confirmed = [&](double start, double end) {
    const auto mean_over = [&](const std::vector<double>& t_s, const std::vector<double>& values) {
      return window_sum(t_s, values, start, end).mean();
    };
    if (!log.gnss.speed_mps.empty()) {
      const auto speed = mean_over(log.gnss.t_s, log.gnss.speed_mps);
      if (speed && std::abs(*speed) > options.max_gnss_speed_mps) return false;
    }
    if (log.imu) {
      const auto rate = mean_over(log.imu->t_s, log.imu->wz_radps);
      if (rate && std::abs(*rate) > options.max_turn_rate_radps) return false;
    }
    return true;
  };
  std::vector<Standstill> standing;
  bool in_standstill = false;
  double start = 0.0;
  for (std::size_t k = 1; k <= wheels.size(); ++k) {
    const bool is_still = k < wheels.size() && still(k) && !wheels.breaks_at(k);
    if (is_still && !in_standstill) {
      in_standstill = true;
      start = wheels.t_s[k - 1];
    }
    if (!is_still && in_standstill) {
      const double end = wheels.t_s[k - 1];
      if (end - start >= options.min_duration_s && confirmed(start, end))
        standing.push_back({start, end});
      in_standstill = false;
    }
  }
  return standing;
}

// The median rate over the standing samples: a sensor's bias reads the same in every one, while
// the creep at the ends of a stop (slowing to it, moving off) is a few samples only; a mean took
// that creep for a bias.
WheelRateBias wheel_rate_bias(const WheelStream& wheels, const std::vector<Standstill>& standing) {
  WheelRateBias bias;
  std::vector<double> rl, rr;
  std::size_t k = 1;
  for (const Standstill& s : standing) {
    while (k < wheels.size() && wheels.t_s[k - 1] < s.start_s) ++k;
    for (; k < wheels.size() && wheels.t_s[k] <= s.end_s; ++k) {
      const double dt = wheels.t_s[k] - wheels.t_s[k - 1];
      rl.push_back(wheels.rev_rl[k] / dt);
      rr.push_back(wheels.rev_rr[k] / dt);
      bias.standing_s += dt;
    }
  }
  if (bias.standing_s > 0.0) {
    bias.rl_rev_per_s = median(std::move(rl));
    bias.rr_rev_per_s = median(std::move(rr));
  }
  return bias;
}

void remove_wheel_rate_bias(WheelStream& wheels, const WheelRateBias& bias) {
  for (std::size_t k = 1; k < wheels.size(); ++k) {
    if (wheels.breaks_at(k)) continue;
    const double dt = wheels.t_s[k] - wheels.t_s[k - 1];
    wheels.rev_rl[k] -= bias.rl_rev_per_s * dt;
    wheels.rev_rr[k] -= bias.rr_rev_per_s * dt;
  }
}

std::optional<double> first_motion_s(const WheelStream& wheels, const OdometryParams& nominal,
                                     double min_speed_mps) {
  for (std::size_t k = 1; k < wheels.size(); ++k) {
    const double dt = wheels.t_s[k] - wheels.t_s[k - 1];
    if (std::abs(body_increment(wheels.increment(k), nominal).distance_m) > min_speed_mps * dt)
      return wheels.t_s[k - 1];
  }
  return std::nullopt;
}

}  // namespace odocal
