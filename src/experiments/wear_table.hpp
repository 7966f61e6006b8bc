#pragma once
// The paper's Table 1 and Fig. 2: the parking-garage scenario driven with each of the paper's
// seven rear tyre-wear pairs and dead-reckoned with the nominal (unworn) circumferences from the
// true start pose; errors against the truth.
//
// Writes into `dir`: table1.csv (one row per wear pair, ours beside the paper's) and paths.csv
// (case, x_m, y_m: the truth as case -1 and each dead-reckoned path, every 5th sample).

#include <filesystem>

#include "experiments/paper_setup.hpp"

namespace odocal::experiments {

void run_wear_table(SimMode mode, const std::filesystem::path& dir);

}  // namespace odocal::experiments
