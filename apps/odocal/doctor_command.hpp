#pragma once
// `odocal doctor LOG`: input mistakes found before they become a wrong calibration.

#include <CLI/CLI.hpp>

namespace odocal::cli {

void add_doctor_command(CLI::App& app);

}  // namespace odocal::cli
