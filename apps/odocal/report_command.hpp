#pragma once

#include <CLI/CLI.hpp>

namespace odocal::cli {

// odocal report RESULT.json --log LOG --out report.html: runs the odocal_report Python package.
void add_report_command(CLI::App& app);

}  // namespace odocal::cli
