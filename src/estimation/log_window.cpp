#include "odocal/estimation/log_window.hpp"

#include <fmt/format.h>

#include "odocal/data/stream_columns.hpp"
#include "odocal/error.hpp"

namespace odocal {
namespace {

template <typename Stream>
Stream between(const Stream& stream, double from_s, double to_s) {
  const auto [first, last] = rows_between(stream.t_s, from_s, to_s);
  return stream_rows(stream, first, last);
}

template <typename Stream>
std::optional<Stream> between(const std::optional<Stream>& stream, double from_s, double to_s) {
  if (!stream) return std::nullopt;
  Stream out = between(*stream, from_s, to_s);
  if (out.t_s.empty()) return std::nullopt;
  return out;
}

}  // namespace

Log slice_log(const Log& log, double from_s, double to_s) {
  Log out;
  out.source = log.source;
  out.vehicle = log.vehicle;
  out.wheels = between(log.wheels, from_s, to_s);
  out.gnss = between(log.gnss, from_s, to_s);
  out.imu = between(log.imu, from_s, to_s);
  out.heading = between(log.heading, from_s, to_s);
  out.truth = between(log.truth, from_s, to_s);
  return out;
}

void start_wheel_chain(WheelStream& wheels) {
  if (wheels.t_s.empty()) return;
  wheels.rev_rl[0] = wheels.rev_rr[0] = 0.0;
  if (!wheels.rev_fl.empty()) wheels.rev_fl[0] = wheels.rev_fr[0] = 0.0;
  if (!wheels.chain_break.empty()) wheels.chain_break[0] = 0;
}

void require_window_holds(std::size_t wheel_samples, std::size_t gnss_fixes, double from_s,
                          double to_s, double wheels_first_s, double wheels_last_s) {
  if (wheel_samples < 2) {
    throw InsufficientDataError(fmt::format(
        "the window {} s to {} s holds {} wheel samples (the log's wheels run from {} s to {} s)",
        from_s, to_s, wheel_samples, wheels_first_s, wheels_last_s));
  }
  if (gnss_fixes == 0)
    throw InsufficientDataError(fmt::format("no GNSS fix between {} s and {} s", from_s, to_s));
}

Log crop_log(const Log& log, double from_s, double to_s) {
  Log out = slice_log(log, from_s, to_s);
  require_window_holds(out.wheels.size(), out.gnss.size(), from_s, to_s, log.wheels.t_s.front(),
                       log.wheels.t_s.back());
  start_wheel_chain(out.wheels);
  return out;
}

}  // namespace odocal
