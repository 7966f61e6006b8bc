#pragma once
// The paper's Figs. 8-11: the section 5 scenario over several noise seeds, calibrated with the
// iterative method, fixed-P and the augmented KF, each judged against the truth and against the
// Cramér–Rao bound of its own log.

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "experiments/paper_setup.hpp"

namespace odocal::experiments {

// One seed: returns (and the caller stores) {seed, true circumferences, crlb_sigma_{rl,rr}_mm,
// methods: {name: method_run_to_json}}.
nlohmann::json run_monte_carlo_seed(const PaperSetup& setup, SimMode mode, std::uint64_t seed);

// Per method over the seeds: mean/max absolute error per wheel and both, mean (bias) and RMS
// error, the RMS of the Cramér–Rao sigma and the RMS error's ratio to it, the fraction of errors
// inside 3 reported sigma, mean dead-reckoning errors and time, and the paper's figure.
nlohmann::json summarise_monte_carlo(const std::vector<nlohmann::json>& seeds);

// summary.csv: one row per method with the fields above.
void write_monte_carlo_summary_csv(const nlohmann::json& summary,
                                   const std::filesystem::path& path);

}  // namespace odocal::experiments
