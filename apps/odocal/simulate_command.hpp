#pragma once
// `odocal simulate`: simulate a drive and its sensors into a log directory.

#include <CLI/CLI.hpp>

namespace odocal::cli {

void add_simulate_command(CLI::App& app);

}  // namespace odocal::cli
