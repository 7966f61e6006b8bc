#pragma once

#include <CLI/CLI.hpp>

namespace odocal::cli {

// `odocal experiment paper --out DIR`: reproduces the paper's tables and figures.
void add_experiment_command(CLI::App& app, int argc, char** argv);

}  // namespace odocal::cli
