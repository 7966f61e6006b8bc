#pragma once
// Writes a simulated drive as a log directory (docs/log-format.md) plus its truth:
// truth.csv, truth.yaml (true parameters) and scenario.yaml (the effective configuration).

#include <filesystem>

#include "odocal/data/log.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {

void write_simulated_log(const sim::SimulatedDrive& drive, const sim::Scenario& scenario,
                         const std::filesystem::path& target);

// The log read_log would return for the written directory (up to CSV rounding), without the
// disk: the raw columns go through the reader's own stream conversions. Truth is left out
// unless asked for.
Log simulated_log(const sim::SimulatedDrive& drive, bool with_truth = false);

}  // namespace odocal
