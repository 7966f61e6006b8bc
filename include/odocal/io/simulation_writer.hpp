#pragma once
// Writes a simulated drive as a log directory (docs/log-format.md) plus its truth:
// truth.csv, truth.yaml (true parameters) and scenario.yaml (the effective configuration).

#include <filesystem>

#include "odocal/sim/simulator.hpp"

namespace odocal {

void write_simulated_log(const sim::SimulatedDrive& drive, const sim::Scenario& scenario,
                         const std::filesystem::path& directory);

}  // namespace odocal
