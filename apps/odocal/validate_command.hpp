#pragma once
// `odocal validate LOG --params result.json`: held-out drift, nominal vs calibrated.

#include <CLI/CLI.hpp>

namespace odocal::cli {

void add_validate_command(CLI::App& app);

}  // namespace odocal::cli
