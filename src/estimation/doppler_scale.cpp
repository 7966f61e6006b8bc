#include "doppler_scale.hpp"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "odocal/error.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/rolled_distance.hpp"

namespace odocal {
namespace {

constexpr double kMinComparedS = 30.0;

bool has_doppler(const Log& log) {
  return log.gnss.speed_mps.size() == log.gnss.size() && log.gnss.size() >= 2 &&
         log.wheels.size() >= 2;
}

// Fixes j and j + 1 are compared: close enough, both speeds read, the wheels rolling fast enough.
// `rolled` counts reversing forward: the Doppler speed has no sign either.
struct FixPairs {
  const Log& log;
  std::vector<double> rolled;
  double min_speed_mps, max_gap_s;

  std::optional<double> wheels_m(std::size_t j) const {
    const GnssStream& gnss = log.gnss;
    const double dt = gnss.t_s[j + 1] - gnss.t_s[j];
    if (dt <= 0.0 || dt > max_gap_s || !std::isfinite(gnss.speed_mps[j]) ||
        !std::isfinite(gnss.speed_mps[j + 1]))
      return std::nullopt;
    const auto from = interpolate_linear(log.wheels.t_s, rolled, gnss.t_s[j]);
    const auto to = interpolate_linear(log.wheels.t_s, rolled, gnss.t_s[j + 1]);
    if (!from || !to || *to - *from < min_speed_mps * dt) return std::nullopt;
    return *to - *from;
  }
  double doppler_m(std::size_t j) const {
    const GnssStream& gnss = log.gnss;
    return 0.5 * (gnss.speed_mps[j] + gnss.speed_mps[j + 1]) * (gnss.t_s[j + 1] - gnss.t_s[j]);
  }
};

std::optional<DopplerScale> scale_of(double doppler_m, double other_m, double compared_s) {
  if (compared_s < kMinComparedS || other_m <= 0.0) return std::nullopt;
  return DopplerScale{doppler_m / other_m, compared_s};
}

std::optional<DopplerScale> over_wheels(const FixPairs& pairs) {
  const GnssStream& gnss = pairs.log.gnss;
  double doppler_m = 0.0, wheels_m = 0.0, compared_s = 0.0;
  for (std::size_t j = 0; j + 1 < gnss.size(); ++j) {
    const std::optional<double> rolled = pairs.wheels_m(j);
    if (!rolled) continue;
    doppler_m += pairs.doppler_m(j);
    wheels_m += *rolled;
    compared_s += gnss.t_s[j + 1] - gnss.t_s[j];
  }
  return scale_of(doppler_m, wheels_m, compared_s);
}

std::optional<DopplerScale> over_positions(const FixPairs& pairs) {
  constexpr double kStretchS = 5.0;
  const GnssStream& gnss = pairs.log.gnss;
  double doppler_m = 0.0, chords_m = 0.0, compared_s = 0.0;
  std::size_t start = 0;
  double stretch_m = 0.0;
  for (std::size_t j = 0; j + 1 < gnss.size(); ++j) {
    if (!pairs.wheels_m(j)) {  // the stretch breaks here
      start = j + 1;
      stretch_m = 0.0;
      continue;
    }
    stretch_m += pairs.doppler_m(j);
    const double duration = gnss.t_s[j + 1] - gnss.t_s[start];
    if (duration < kStretchS) continue;
    doppler_m += stretch_m;
    chords_m += std::hypot(gnss.x_m[j + 1] - gnss.x_m[start], gnss.y_m[j + 1] - gnss.y_m[start]);
    compared_s += duration;
    start = j + 1;
    stretch_m = 0.0;
  }
  return scale_of(doppler_m, chords_m, compared_s);
}

}  // namespace

std::string likely_speed_unit(double ratio) {
  struct Unit {
    const char* name;
    double per_mps;
  };
  for (const Unit unit : {Unit{"km/h", 3.6}, Unit{"mph", 2.2369}, Unit{"knots", 1.9438},
                          Unit{"cm/s", 100.0}, Unit{"mm/s", 1000.0}}) {
    if (std::abs(ratio / unit.per_mps - 1.0) < 0.05)
      return fmt::format("the speed is in {} (x{:g})", unit.name, unit.per_mps);
  }
  return {};
}

std::optional<DopplerScale> doppler_over_wheels(const Log& log, const OdometryParams& nominal,
                                                double min_speed_mps, double max_gap_s) {
  if (!has_doppler(log)) return std::nullopt;
  return over_wheels({log, rolled_distance_m(log.wheels, nominal), min_speed_mps, max_gap_s});
}

std::optional<DopplerScale> doppler_over_positions(const Log& log, const OdometryParams& nominal,
                                                   double min_speed_mps, double max_gap_s) {
  if (!has_doppler(log)) return std::nullopt;
  return over_positions({log, rolled_distance_m(log.wheels, nominal), min_speed_mps, max_gap_s});
}

void check_doppler_scale(const Log& log, const OdometryParams& nominal) {
  const auto off = [](const std::optional<DopplerScale>& s) {
    return s && std::abs(s->ratio - 1.0) > 0.1;
  };
  if (!has_doppler(log)) return;
  const FixPairs pairs{log, rolled_distance_m(log.wheels, nominal), kDopplerJudgedSpeedMps,
                       kDopplerMaxFixGapS};
  const std::optional<DopplerScale> wheels = over_wheels(pairs);
  if (!off(wheels)) return;
  const std::optional<DopplerScale> positions = over_positions(pairs);
  if (positions && !off(positions)) return;
  const DopplerScale& judged = positions ? *positions : *wheels;
  const std::string unit = likely_speed_unit(judged.ratio);
  throw InputError(
      {"gnss.csv", 0, "speed_mps"},
      fmt::format(
          "the Doppler speed reads {:.3f} times the {} speed over {:.0f} s of driving above "
          "{:g} m/s ({:.3f} times the wheels' at the nominal circumferences): {}; convert it "
          "to m/s or drop the column",
          judged.ratio, positions ? "positions'" : "wheels'", judged.compared_s,
          kDopplerJudgedSpeedMps, wheels->ratio,
          unit.empty() ? "it is not a speed over ground in m/s" : unit));
}

}  // namespace odocal
