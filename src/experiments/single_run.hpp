#pragma once
// The paper's Figs. 4-7 and 12 on one noise seed of the section 5 scenario: the speed profile,
// the path, every iteration's dead-reckoning errors and circumferences (iterative and fixed-P,
// run on through max_iterations for illustration as in the paper, with the stop rule's choice
// recorded), and the augmented KF's parameter time series.
//
// Writes into `dir`: speed.csv, path.csv, gnss.csv, iterations.csv, augmented.csv, summary.json.

#include <cstdint>
#include <filesystem>

#include "experiments/paper_setup.hpp"

namespace odocal::experiments {

void run_single(const PaperSetup& setup, SimMode mode, std::uint64_t seed,
                const std::filesystem::path& dir);

}  // namespace odocal::experiments
