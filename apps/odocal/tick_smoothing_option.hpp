#pragma once
// `--tick-smoothing S`: how dead reckoning treats encoder ticks (tick_dequantisation.hpp), the
// same option wherever the CLI dead-reckons.

#include <CLI/CLI.hpp>

#include "number_checks.hpp"

namespace odocal::cli {

inline void add_tick_smoothing_option(CLI::App& command, double& tick_smoothing_s) {
  command
      .add_option("--tick-smoothing", tick_smoothing_s,
                  "Average encoder tick counts over +-S s before dead reckoning (their "
                  "quantisation); 0: the counts as they are")
      ->capture_default_str()
      ->check(finite_in(0.0, 10.0));
}

}  // namespace odocal::cli
