#include "experiments/single_run.hpp"

#include "experiments/json_file.hpp"
#include "experiments/truth_comparison.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/io/text_output.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal::experiments {
namespace {

constexpr std::size_t kSpeedStride = 5;  // 10 Hz of the 50 Hz truth
constexpr std::size_t kPathStride = 10;
constexpr std::size_t kGnssStride = 50;
constexpr std::size_t kParameterStride = 10;

void write_speed_and_path(const PoseStream& truth, const GnssStream& gnss,
                          const std::filesystem::path& dir) {
  write_text_file(dir / "speed.csv", [&](TextBuffer& out) {
    out.print("t_s,speed_mps\n");
    for (std::size_t k = kSpeedStride; k < truth.size(); k += kSpeedStride) {
      const double dt = truth.t_s[k] - truth.t_s[k - 1];
      const double speed = (truth.pose[k] - truth.pose[k - 1]).head<2>().norm() / dt;
      out.print("{:.2f},{:.3f}\n", truth.t_s[k], speed);
    }
  });
  write_text_file(dir / "path.csv", [&](TextBuffer& out) {
    out.print("t_s,x_m,y_m\n");
    for (std::size_t k = 0; k < truth.size(); k += kPathStride)
      out.print("{:.2f},{:.3f},{:.3f}\n", truth.t_s[k], truth.pose[k].x(), truth.pose[k].y());
  });
  write_text_file(dir / "gnss.csv", [&](TextBuffer& out) {
    out.print("t_s,x_m,y_m\n");
    for (std::size_t k = 0; k < gnss.size(); k += kGnssStride)
      out.print("{:.2f},{:.3f},{:.3f}\n", gnss.t_s[k], gnss.x_m[k], gnss.y_m[k]);
  });
}

void write_iterations(const std::vector<const IterativeSummary*>& results,
                      const std::filesystem::path& path) {
  write_text_file(path, [&](TextBuffer& out) {
    out.print(
        "method,iteration,c_rl_m,c_rr_m,mean_position_m,max_position_m,mean_heading_deg,"
        "max_heading_deg,score\n");
    for (const IterativeSummary* result : results) {
      for (const IterationRecord& r : result->iterations) {
        out.print("{},{},{:.7f},{:.7f},{:.4f},{:.4f},{:.5f},{:.5f},{:.5f}\n",
                  method_name(result->method), r.iteration, r.circumference_rl_m,
                  r.circumference_rr_m, r.errors.mean_position_m, r.errors.max_position_m,
                  deg_from_rad(r.errors.mean_heading_rad), deg_from_rad(r.errors.max_heading_rad),
                  r.score);
      }
    }
  });
}

void write_parameter_series(const AugmentedSummary& augmented, const std::filesystem::path& path) {
  write_text_file(path, [&](TextBuffer& out) {
    out.print("t_s,c_rl_m,c_rr_m\n");
    for (std::size_t k = 0; k < augmented.parameter_t_s.size(); k += kParameterStride) {
      out.print("{:.2f},{:.7f},{:.7f}\n", augmented.parameter_t_s[k], augmented.parameter_c_rl_m[k],
                augmented.parameter_c_rr_m[k]);
    }
  });
}

}  // namespace

void run_single(const PaperSetup& setup, SimMode mode, std::uint64_t seed,
                const std::filesystem::path& dir) {
  const sim::Scenario scenario = paper_scenario(setup, mode, seed);
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive, true);
  const OdometryParams& truth = drive.true_params;
  write_speed_and_path(*log.truth, log.gnss, dir);

  nlohmann::json methods = nlohmann::json::object();
  std::vector<IterativeSummary> illustrations;  // run on through max_iterations
  for (const CalibrationMethod method :
       {CalibrationMethod::kIterative, CalibrationMethod::kFixedP, CalibrationMethod::kAugmented}) {
    CalibrationConfig options = method_options(method, mode);
    const MethodRun run = run_method(log, truth, options);
    methods[method_name(method)] = method_run_to_json(run);
    if (method == CalibrationMethod::kAugmented) {
      write_parameter_series(std::get<AugmentedSummary>(run.result), dir / "augmented.csv");
      continue;
    }
    options.iterative.patience = options.iterative.max_iterations;
    illustrations.push_back(std::get<IterativeSummary>(calibrate(log, options)));
    // Iterations are deterministic: the illustration repeats the stopped run's first ones.
    illustrations.back().chosen_iteration = std::get<IterativeSummary>(run.result).chosen_iteration;
  }
  write_iterations({&illustrations[0], &illustrations[1]}, dir / "iterations.csv");

  const CramerRaoBound bound = scenario_cramer_rao_bound(scenario, log, truth);
  write_json_file(dir / "summary.json",
                  {{"mode", mode_name(mode)},
                   {"seed", seed},
                   {"distance_m", drive.distance_m},
                   {"duration_s", log.wheels.t_s.back() - log.wheels.t_s.front()},
                   {"true_circumference_rl_m", truth.circumference_rl_m},
                   {"true_circumference_rr_m", truth.circumference_rr_m},
                   {"nominal_circumference_rl_m", log.vehicle.nominal_params().circumference_rl_m},
                   {"nominal_circumference_rr_m", log.vehicle.nominal_params().circumference_rr_m},
                   {"chosen_iteration",
                    {{"iterative", illustrations[0].chosen_iteration},
                     {"fixed-p", illustrations[1].chosen_iteration}}},
                   {"crlb_sigma_rl_mm", 1e3 * bound.sigma_c_rl_m},
                   {"crlb_sigma_rr_mm", 1e3 * bound.sigma_c_rr_m},
                   {"methods", methods},
                   {"paper",
                    {{"error_rl_mm", kPaperSingleRunErrorRlMm},
                     {"error_rr_mm", kPaperSingleRunErrorRrMm},
                     {"mean_position_m", kPaperSingleRunMeanPositionM},
                     {"max_position_m", kPaperSingleRunMaxPositionM},
                     {"mean_heading_deg", kPaperSingleRunMeanHeadingDeg},
                     {"max_heading_deg", kPaperSingleRunMaxHeadingDeg}}}});
}

}  // namespace odocal::experiments
