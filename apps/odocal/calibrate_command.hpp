#pragma once
// `odocal calibrate LOG`: estimate the rear wheel circumferences from a log (paper sections 3-5,
// or the batch estimator); `--print-config` prints the configuration file.

#include <CLI/CLI.hpp>

namespace odocal::cli {

void add_calibrate_command(CLI::App& app);

}  // namespace odocal::cli
