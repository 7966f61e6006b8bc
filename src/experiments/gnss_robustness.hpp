#pragma once
// Beyond the paper: the section 5 scenario (ideal mode) with degraded GNSS, a first-order
// Gauss-Markov error (sigma 2 m, tau 60 s) on top of the white noise, 2 % outliers of 20-50 m and
// a 120 s outage, calibrated by the batch estimator (told about the Gauss-Markov error) and by the
// iterative method; the batch estimator also on the clean GNSS of the same seed, for the ratio.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "experiments/paper_setup.hpp"

namespace odocal::experiments {

struct DegradedGnss {
  double gauss_markov_sigma_m = 2.0;
  double gauss_markov_tau_s = 60.0;
  double outlier_rate = 0.02;
  double outlier_min_m = 20.0;
  double outlier_max_m = 50.0;
  double outage_start_s = 250.0;
  double outage_duration_s = 120.0;
};

// {seed, clean: {batch}, degraded: {batch, iterative}} with method_run_to_json entries.
nlohmann::json run_robustness_seed(const PaperSetup& setup, const DegradedGnss& gnss,
                                   std::uint64_t seed);

// Per configuration: RMS and mean |error|, the batch's degraded/clean RMS ratio, and the share of
// batch errors inside 3 reported sigma.
nlohmann::json summarise_robustness(const std::vector<nlohmann::json>& seeds);

}  // namespace odocal::experiments
