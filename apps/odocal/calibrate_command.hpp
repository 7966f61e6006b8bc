#pragma once
// `odocal calibrate LOG`: estimate the rear wheel circumferences from a log (paper sections 3-5).

#include <CLI/CLI.hpp>

#include "odocal/estimation/calibration.hpp"

namespace odocal::cli {

void add_calibrate_command(CLI::App& app);

// The human-readable report shared by `calibrate` and `demo`.
void print_calibration_report(const CalibrationResult& result);

}  // namespace odocal::cli
