#include "experiments/monte_carlo.hpp"

#include <algorithm>
#include <cmath>

#include "experiments/truth_comparison.hpp"
#include "odocal/error.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/io/text_output.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal::experiments {
namespace {

constexpr CalibrationMethod kMethods[] = {CalibrationMethod::kIterative, CalibrationMethod::kFixedP,
                                          CalibrationMethod::kAugmented, CalibrationMethod::kBatch};

// The paper's mean absolute error for the method; null for methods the paper does not have.
nlohmann::json paper_figure(CalibrationMethod method) {
  switch (method) {
    case CalibrationMethod::kIterative:
      return kPaperIterativeMeanAbsErrorMm;
    case CalibrationMethod::kFixedP:
      return kPaperFixedPMeanAbsErrorMm;
    case CalibrationMethod::kAugmented:
      return kPaperAugmentedMeanAbsErrorMm;
    case CalibrationMethod::kBatch:
      break;
  }
  return nullptr;
}

// Accumulates one method's numbers over the seeds.
struct MethodStats {
  std::vector<double> errors_rl, errors_rr;
  double crlb_variance_sum = 0.0, crlb_exact_counts_variance_sum = 0.0;
  int within_3_sigma = 0;
  double dr_position_sum = 0.0, dr_heading_sum = 0.0, milliseconds_sum = 0.0;

  void add(const nlohmann::json& seed, const nlohmann::json& run) {
    const double e_rl = run.at("error_rl_mm"), e_rr = run.at("error_rr_mm");
    errors_rl.push_back(e_rl);
    errors_rr.push_back(e_rr);
    const double s_rl = seed.at("crlb_sigma_rl_mm"), s_rr = seed.at("crlb_sigma_rr_mm");
    crlb_variance_sum += s_rl * s_rl + s_rr * s_rr;
    const double x_rl = seed.at("crlb_exact_counts_sigma_rl_mm");
    const double x_rr = seed.at("crlb_exact_counts_sigma_rr_mm");
    crlb_exact_counts_variance_sum += x_rl * x_rl + x_rr * x_rr;
    within_3_sigma += std::abs(e_rl) < 3.0 * run.at("reported_sigma_rl_mm").get<double>();
    within_3_sigma += std::abs(e_rr) < 3.0 * run.at("reported_sigma_rr_mm").get<double>();
    dr_position_sum += run.at("dr_mean_position_m").get<double>();
    dr_heading_sum += run.at("dr_mean_heading_deg").get<double>();
    milliseconds_sum += run.at("milliseconds").get<double>();
  }

  nlohmann::json summary(CalibrationMethod method) const {
    const double n = static_cast<double>(errors_rl.size());
    double abs_rl = 0, abs_rr = 0, sum = 0, squares = 0, max_abs = 0;
    for (std::size_t i = 0; i < errors_rl.size(); ++i) {
      abs_rl += std::abs(errors_rl[i]);
      abs_rr += std::abs(errors_rr[i]);
      sum += errors_rl[i] + errors_rr[i];
      squares += errors_rl[i] * errors_rl[i] + errors_rr[i] * errors_rr[i];
      max_abs = std::max({max_abs, std::abs(errors_rl[i]), std::abs(errors_rr[i])});
    }
    const double rms = std::sqrt(squares / (2 * n));
    const double crlb = std::sqrt(crlb_variance_sum / (2 * n));
    return {{"method", method_name(method)},
            {"seeds", errors_rl.size()},
            {"mean_abs_error_rl_mm", abs_rl / n},
            {"mean_abs_error_rr_mm", abs_rr / n},
            {"mean_abs_error_mm", (abs_rl + abs_rr) / (2 * n)},
            {"max_abs_error_mm", max_abs},
            {"mean_error_mm", sum / (2 * n)},
            {"rms_error_mm", rms},
            {"crlb_sigma_mm", crlb},
            {"rms_over_crlb", rms / crlb},
            {"crlb_exact_counts_sigma_mm", std::sqrt(crlb_exact_counts_variance_sum / (2 * n))},
            {"within_3_reported_sigma", within_3_sigma / (2 * n)},
            {"mean_dr_position_m", dr_position_sum / n},
            {"mean_dr_heading_deg", dr_heading_sum / n},
            {"mean_milliseconds", milliseconds_sum / n},
            {"paper_mean_abs_error_mm", paper_figure(method)}};
  }
};

}  // namespace

nlohmann::json run_monte_carlo_seed(const PaperSetup& setup, SimMode mode, std::uint64_t seed) {
  const sim::Scenario scenario = paper_scenario(setup, mode, seed);
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive, true);
  const CramerRaoBound bound = scenario_cramer_rao_bound(scenario, log, drive.true_params);
  const CramerRaoBound exact_counts =
      scenario_cramer_rao_bound(scenario, log, drive.true_params, CountModel::kExact);
  nlohmann::json methods = nlohmann::json::object();
  for (const CalibrationMethod method : kMethods) {
    methods[method_name(method)] =
        method_run_to_json(run_method(log, drive.true_params, method_options(method, mode)));
  }
  return {{"mode", mode_name(mode)},
          {"seed", seed},
          {"true_circumference_rl_m", drive.true_params.circumference_rl_m},
          {"true_circumference_rr_m", drive.true_params.circumference_rr_m},
          {"crlb_sigma_rl_mm", 1e3 * bound.sigma_c_rl_m},
          {"crlb_sigma_rr_mm", 1e3 * bound.sigma_c_rr_m},
          {"crlb_exact_counts_sigma_rl_mm", 1e3 * exact_counts.sigma_c_rl_m},
          {"crlb_exact_counts_sigma_rr_mm", 1e3 * exact_counts.sigma_c_rr_m},
          {"methods", methods}};
}

nlohmann::json summarise_monte_carlo(const std::vector<nlohmann::json>& seeds) {
  if (seeds.empty()) throw Error("no Monte-Carlo seeds to summarise");
  nlohmann::json summary = nlohmann::json::array();
  for (const CalibrationMethod method : kMethods) {
    MethodStats stats;
    for (const nlohmann::json& seed : seeds)
      stats.add(seed, seed.at("methods").at(method_name(method)));
    summary.push_back(stats.summary(method));
  }
  return summary;
}

void write_monte_carlo_summary_csv(const nlohmann::json& summary,
                                   const std::filesystem::path& path) {
  const char* const columns[] = {"seeds",
                                 "mean_abs_error_rl_mm",
                                 "mean_abs_error_rr_mm",
                                 "mean_abs_error_mm",
                                 "max_abs_error_mm",
                                 "mean_error_mm",
                                 "rms_error_mm",
                                 "crlb_sigma_mm",
                                 "rms_over_crlb",
                                 "crlb_exact_counts_sigma_mm",
                                 "within_3_reported_sigma",
                                 "mean_dr_position_m",
                                 "mean_dr_heading_deg",
                                 "mean_milliseconds",
                                 "paper_mean_abs_error_mm"};
  write_text_file(path, [&](TextBuffer& out) {
    out.print("method");
    for (const char* column : columns) out.print(",{}", column);
    out.print("\n");
    for (const nlohmann::json& row : summary) {
      out.print("{}", row.at("method").get<std::string>());
      for (const char* column : columns) out.print(",{}", row.at(column).dump());
      out.print("\n");
    }
  });
}

}  // namespace odocal::experiments
