#include "experiments/gnss_robustness.hpp"

#include <cmath>

#include "experiments/truth_comparison.hpp"
#include "odocal/error.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal::experiments {
namespace {

nlohmann::json calibrate_json(const Log& log, const OdometryParams& truth,
                              const CalibrationConfig& options) {
  return method_run_to_json(run_method(log, truth, options));
}

}  // namespace

nlohmann::json run_robustness_seed(const PaperSetup& setup, const DegradedGnss& gnss,
                                   std::uint64_t seed) {
  const sim::Scenario clean_scenario = paper_scenario(setup, SimMode::kIdeal, seed);
  const sim::SimulatedDrive clean = sim::simulate(clean_scenario);
  sim::Scenario scenario = clean_scenario;
  scenario.gnss.gauss_markov_sigma_m = gnss.gauss_markov_sigma_m;
  scenario.gnss.gauss_markov_tau_s = gnss.gauss_markov_tau_s;
  scenario.gnss.outlier_rate = gnss.outlier_rate;
  scenario.gnss.outlier_min_m = gnss.outlier_min_m;
  scenario.gnss.outlier_max_m = gnss.outlier_max_m;
  scenario.gnss.outages = {{gnss.outage_start_s, gnss.outage_duration_s}};
  const sim::SimulatedDrive degraded = sim::simulate(scenario);

  const CalibrationConfig batch = method_options(CalibrationMethod::kBatch, SimMode::kIdeal);
  CalibrationConfig batch_told = batch;
  batch_told.batch.gnss_gauss_markov_sigma_m = gnss.gauss_markov_sigma_m;
  batch_told.batch.gnss_gauss_markov_tau_s = gnss.gauss_markov_tau_s;
  const Log clean_log = simulated_log(clean, true);
  const Log degraded_log = simulated_log(degraded, true);
  const auto bound_mm = [](const sim::Scenario& s, const Log& log, const OdometryParams& truth) {
    return 1e3 * scenario_cramer_rao_bound(s, log, truth).rms_sigma_circumference_m();
  };
  return {{"seed", seed},
          {"crlb_sigma_clean_mm", bound_mm(clean_scenario, clean_log, clean.true_params)},
          {"crlb_sigma_degraded_mm", bound_mm(scenario, degraded_log, degraded.true_params)},
          {"clean", {{"batch", calibrate_json(clean_log, clean.true_params, batch)}}},
          {"degraded",
           {{"batch", calibrate_json(degraded_log, degraded.true_params, batch_told)},
            {"iterative",
             calibrate_json(degraded_log, degraded.true_params,
                            method_options(CalibrationMethod::kIterative, SimMode::kIdeal))}}}};
}

nlohmann::json summarise_robustness(const std::vector<nlohmann::json>& seeds) {
  if (seeds.empty()) throw Error("no robustness seeds to summarise");
  const auto stats = [&](const char* gnss, const char* method) {
    double squares = 0.0, absolute = 0.0;
    int inside = 0, count = 0;
    for (const nlohmann::json& seed : seeds) {
      const nlohmann::json& run = seed.at(gnss).at(method);
      for (const char* wheel : {"rl", "rr"}) {
        const double error = run.at(std::string("error_") + wheel + "_mm").get<double>();
        const double sigma = run.at(std::string("reported_sigma_") + wheel + "_mm").get<double>();
        squares += error * error;
        absolute += std::abs(error);
        inside += std::abs(error) < 3.0 * sigma;
        ++count;
      }
    }
    return nlohmann::json{{"gnss", gnss},
                          {"method", method},
                          {"rms_error_mm", std::sqrt(squares / count)},
                          {"mean_abs_error_mm", absolute / count},
                          {"within_3_reported_sigma", static_cast<double>(inside) / count}};
  };
  double clean_bound = 0.0, degraded_bound = 0.0;  // RMS over seeds
  const auto seed_count = static_cast<double>(seeds.size());
  for (const nlohmann::json& seed : seeds) {
    clean_bound += std::pow(seed.at("crlb_sigma_clean_mm").get<double>(), 2) / seed_count;
    degraded_bound += std::pow(seed.at("crlb_sigma_degraded_mm").get<double>(), 2) / seed_count;
  }
  const nlohmann::json clean = stats("clean", "batch");
  const nlohmann::json degraded = stats("degraded", "batch");
  return {{"rows", {clean, degraded, stats("degraded", "iterative")}},
          {"seeds", seeds.size()},
          {"batch_degraded_over_clean_rms",
           degraded.at("rms_error_mm").get<double>() / clean.at("rms_error_mm").get<double>()},
          {"crlb_sigma_clean_mm", std::sqrt(clean_bound)},
          {"crlb_sigma_degraded_mm", std::sqrt(degraded_bound)}};
}

}  // namespace odocal::experiments
