#pragma once
// `odocal demo`: the main job on a built-in default: simulate the paper's scenario with worn
// tyres, calibrate it as a user would (from the written log, without truth), and compare.

#include <CLI/CLI.hpp>

namespace odocal::cli {

void add_demo_command(CLI::App& app);

}  // namespace odocal::cli
