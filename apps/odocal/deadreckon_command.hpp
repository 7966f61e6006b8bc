#pragma once
// `odocal deadreckon LOG`: integrate the wheel odometry over a whole log and report its error.

#include <CLI/CLI.hpp>

namespace odocal::cli {

void add_deadreckon_command(CLI::App& app);

}  // namespace odocal::cli
