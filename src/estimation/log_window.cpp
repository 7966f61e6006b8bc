#include "odocal/estimation/log_window.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "odocal/error.hpp"

namespace odocal {
namespace {

// [first, last) of the samples of `t_s` inside [from, to].
std::pair<std::size_t, std::size_t> inside(const std::vector<double>& t_s, double from, double to) {
  const auto first = std::lower_bound(t_s.begin(), t_s.end(), from);
  const auto last = std::upper_bound(first, t_s.end(), to);
  return {static_cast<std::size_t>(first - t_s.begin()),
          static_cast<std::size_t>(last - t_s.begin())};
}

template <typename T>
void keep(std::vector<T>& values, std::pair<std::size_t, std::size_t> range) {
  if (values.empty()) return;
  values.erase(values.begin() + static_cast<std::ptrdiff_t>(range.second), values.end());
  values.erase(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(range.first));
}

}  // namespace

Log crop_log(const Log& log, double from_s, double to_s) {
  Log out = log;
  const auto wheels = inside(log.wheels.t_s, from_s, to_s);
  if (wheels.second - wheels.first < 2) {
    throw InsufficientDataError(fmt::format(
        "the window {} s to {} s holds {} wheel samples (the log's wheels run from {} s to {} s)",
        from_s, to_s, wheels.second - wheels.first, log.wheels.t_s.front(), log.wheels.t_s.back()));
  }
  for (auto* v : {&out.wheels.t_s, &out.wheels.rev_rl, &out.wheels.rev_rr, &out.wheels.rev_fl,
                  &out.wheels.rev_fr})
    keep(*v, wheels);
  keep(out.wheels.chain_break, wheels);
  out.wheels.rev_rl[0] = out.wheels.rev_rr[0] = 0.0;
  if (!out.wheels.rev_fl.empty()) out.wheels.rev_fl[0] = out.wheels.rev_fr[0] = 0.0;
  if (!out.wheels.chain_break.empty()) out.wheels.chain_break[0] = 0;

  const auto gnss = inside(log.gnss.t_s, from_s, to_s);
  if (gnss.second == gnss.first)
    throw InsufficientDataError(fmt::format("no GNSS fix between {} s and {} s", from_s, to_s));
  for (auto* v : {&out.gnss.t_s, &out.gnss.x_m, &out.gnss.y_m, &out.gnss.altitude_m,
                  &out.gnss.sigma_m, &out.gnss.speed_mps})
    keep(*v, gnss);
  if (out.imu) {
    const auto imu = inside(log.imu->t_s, from_s, to_s);
    for (auto* v : {&out.imu->t_s, &out.imu->ax_mps2, &out.imu->ay_mps2, &out.imu->wz_radps})
      keep(*v, imu);
    if (out.imu->t_s.empty()) out.imu.reset();
  }
  if (out.heading) {
    const auto heading = inside(log.heading->t_s, from_s, to_s);
    for (auto* v : {&out.heading->t_s, &out.heading->heading_rad}) keep(*v, heading);
    if (out.heading->t_s.empty()) out.heading.reset();
  }
  if (out.truth) {
    const auto truth = inside(log.truth->t_s, from_s, to_s);
    keep(out.truth->t_s, truth);
    keep(out.truth->pose, truth);
    if (out.truth->t_s.empty()) out.truth.reset();
  }
  return out;
}

}  // namespace odocal
