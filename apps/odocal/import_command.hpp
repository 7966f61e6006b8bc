#pragma once
// `odocal import csv --map MAP.yaml --out LOG`: convert any CSV logger's files into a log.

#include <CLI/CLI.hpp>

namespace odocal::cli {

void add_import_command(CLI::App& app);

}  // namespace odocal::cli
