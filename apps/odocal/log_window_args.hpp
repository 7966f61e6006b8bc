#pragma once
// `--from` / `--to`: the part of a log a command uses, in seconds on the log's clock.

#include <CLI/CLI.hpp>
#include <optional>

#include "odocal/data/log.hpp"

namespace odocal::cli {

struct LogWindowArgs {
  std::optional<double> from_s;
  std::optional<double> to_s;

  void add_to(CLI::App& command);
  // The log cut to the window (the log itself when neither is given).
  Log apply(Log log) const;
};

}  // namespace odocal::cli
