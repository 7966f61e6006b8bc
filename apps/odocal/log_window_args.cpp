#include "log_window_args.hpp"

#include <limits>

#include "number_checks.hpp"
#include "odocal/estimation/log_window.hpp"

namespace odocal::cli {

void LogWindowArgs::add_to(CLI::App& command) {
  command.add_option("--from", from_s, "Use the log from this time on (s, the log's clock)")
      ->check(finite_in(-1e12, 1e12));
  command.add_option("--to", to_s, "Use the log up to this time (s, the log's clock)")
      ->check(finite_in(-1e12, 1e12));
}

Log LogWindowArgs::apply(Log log) const {
  if (!from_s && !to_s) return log;
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  return crop_log(log, from_s.value_or(-kInfinity), to_s.value_or(kInfinity));
}

}  // namespace odocal::cli
