#include "experiments/truth_comparison.hpp"

#include <chrono>
#include <cmath>

#include "odocal/error.hpp"
#include "odocal/estimation/dead_reckoning.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/model/angle.hpp"

namespace odocal::experiments {
namespace {

const PoseStream& truth_of(const Log& log) {
  if (!log.truth || log.truth->size() == 0)
    throw Error("the experiment needs the simulator's truth");
  return *log.truth;
}

}  // namespace

TruthComparison compare_with_truth(const CalibrationSummary& result, const Log& log,
                                   const OdometryParams& truth) {
  const PoseStream& truth_path = truth_of(log);
  TruthComparison c;
  c.error_rl_mm = 1e3 * (result.estimate.circumference_rl_m - truth.circumference_rl_m);
  c.error_rr_mm = 1e3 * (result.estimate.circumference_rr_m - truth.circumference_rr_m);
  c.reported_sigma_rl_mm = 1e3 * result.sigma_rl_m();
  c.reported_sigma_rr_mm = 1e3 * result.sigma_rr_m();
  // A result with a tyre model dead-reckons the wheels as its model counts them.
  const PoseStream path = dead_reckon(
      result.tyre_model.plain() ? log.wheels
                                : with_tyre_model(log, result.estimate, result.tyre_model),
      result.estimate, truth_path.pose.front());
  c.dead_reckoning = trajectory_errors(path, reference_from_poses(truth_path, "truth"));
  return c;
}

CramerRaoBound scenario_cramer_rao_bound(const sim::Scenario& scenario, const Log& log,
                                         const OdometryParams& truth, CountModel counts) {
  return circumference_cramer_rao_bound(
      log, truth, truth_of(log).pose.front(),
      {.gnss_sigma_m = std::hypot(scenario.gnss.sigma_m, scenario.gnss.gauss_markov_sigma_m),
       .heading_sigma_rad = scenario.heading.sigma_rad,
       .quantisation_sigma_rev =
           counts == CountModel::kQuantised ? encoder_quantisation_sigma_rev(log) : 0.0,
       .gnss_gauss_markov_sigma_m = scenario.gnss.gauss_markov_sigma_m,
       .gnss_gauss_markov_tau_s = scenario.gnss.gauss_markov_tau_s});
}

MethodRun run_method(const Log& log, const OdometryParams& truth,
                     const CalibrationConfig& options) {
  MethodRun run;
  const auto begin = std::chrono::steady_clock::now();
  run.result = calibrate(log, options);
  run.milliseconds =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
  run.comparison = compare_with_truth(core(run.result), log, truth);
  return run;
}

nlohmann::json method_run_to_json(const MethodRun& run) {
  const CalibrationSummary& result = core(run.result);
  const auto* iterative = std::get_if<IterativeSummary>(&run.result);
  const TruthComparison& c = run.comparison;
  return {{"method", method_name(result.method)},
          {"termination", enum_name(result.termination)},
          {"usable", result.usable()},
          {"circumference_rl_m", result.estimate.circumference_rl_m},
          {"circumference_rr_m", result.estimate.circumference_rr_m},
          {"error_rl_mm", c.error_rl_mm},
          {"error_rr_mm", c.error_rr_mm},
          {"reported_sigma_rl_mm", c.reported_sigma_rl_mm},
          {"reported_sigma_rr_mm", c.reported_sigma_rr_mm},
          {"chosen_iteration", iterative ? iterative->chosen_iteration : 0},
          {"iterations_run", iterative ? iterative->iterations.size() : 0},
          {"dr_mean_position_m", c.dead_reckoning.mean_position_m},
          {"dr_max_position_m", c.dead_reckoning.max_position_m},
          {"dr_mean_heading_deg", deg_from_rad(c.dead_reckoning.mean_heading_rad)},
          {"dr_max_heading_deg", deg_from_rad(c.dead_reckoning.max_heading_rad)},
          {"milliseconds", run.milliseconds}};
}

}  // namespace odocal::experiments
