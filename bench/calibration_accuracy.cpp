// Monte-Carlo accuracy of the calibration methods on the simulator (issue #4's figures):
// for each noise seed, simulate the paper's scenario (3 laps of Hockenheim when the shared track
// is present, else the built-in circuit; --ideal; the paper's sensor noise), calibrate with each
// method, and report the absolute circumference errors and dead-reckoning errors.
//
//   build/bench/odocal_calibration_accuracy [--seeds 10] [--q 2] [--window 10]
//       [--start aligned-window] [--reference filter] [--wheels ticks] [--track FILE|builtin]
//       [--methods iterative,fixed-p,augmented,batch] [--config OPTIONS.yaml] [--laps 3]
//       [--grade 0.06 [--no-altitude]]
// Also prints the Cramér–Rao sigma of c_RL/c_RR (GNSS and heading noise, encoder quantisation;
// and with counts taken as exact, for comparison) and each method's RMS
// error as a multiple of it.

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <numeric>

#include "experiments/paper_setup.hpp"
#include "experiments/truth_comparison.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/io/calibration_io.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

using namespace odocal;

namespace {

struct Stats {
  std::vector<double> abs_error_mm;  // both wheels, every seed
  std::vector<double> mean_position_m, mean_heading_deg, milliseconds, reported_sigma_mm;
};

double mean(const std::vector<double>& v) {
  return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}
double max_of(const std::vector<double>& v) { return *std::max_element(v.begin(), v.end()); }
double rms(const std::vector<double>& v) {
  return std::sqrt(std::inner_product(v.begin(), v.end(), v.begin(), 0.0) /
                   static_cast<double>(v.size()));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Monte-Carlo accuracy of odocal's calibration methods"};
  int seeds = 10;
  double q = IterativeOptions{}.decay_exponent_q;
  int window = IterativeOptions{}.ls_window_samples;
  std::string start = "aligned-window", reference = "filter", wheels = "ticks";
  std::string track =
      std::string(ODOCAL_SOURCE_DIR) + "/../shared/data/tracks/hockenheim/track.csv";
  double wear_rl = 1.5, wear_rr = 1.0;
  std::vector<std::string> method_names{"iterative", "fixed-p", "augmented"};
  std::string config;
  int laps = 3;
  double grade = 0.0;
  bool no_altitude = false;
  app.add_option("--seeds", seeds);
  app.add_option("--q", q);
  app.add_option("--window", window);
  app.add_option("--start", start)->check(CLI::IsMember(enum_name_list<DeadReckoningStart>()));
  app.add_option("--reference", reference)->check(CLI::IsMember(enum_name_list<ReferenceMode>()));
  app.add_option("--wheels", wheels)->check(CLI::IsMember({"ticks", "rad"}));
  app.add_option("--track", track, "TUMFTM centreline, or 'builtin' for the built-in circuit");
  app.add_option("--wear-rl", wear_rl);
  app.add_option("--wear-rr", wear_rr);
  app.add_option("--methods", method_names)
      ->delimiter(',')
      ->check(CLI::IsMember(enum_name_list<CalibrationMethod>()));
  app.add_option("--config", config, "Calibration options YAML (as odocal calibrate --config)")
      ->check(CLI::ExistingFile);
  app.add_option("--laps", laps)->check(CLI::PositiveNumber);
  app.add_option("--grade", grade, "Hills along the road: maximum grade (e.g. 0.06)")
      ->check(CLI::Range(0.0, 0.3));
  app.add_flag("--no-altitude", no_altitude, "Calibrate without the GNSS altitude (planar)");
  CLI11_PARSE(app, argc, argv);

  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  std::string where = "built-in circuit";
  if (track != "builtin" && std::filesystem::exists(track)) {
    use_track_file(scenario, track);
    where = "Hockenheim (" + track + ")";
  }
  scenario.route.laps = laps;
  scenario.route.terrain.max_grade = grade;
  scenario.vehicle.wear_rl_mm = wear_rl;
  scenario.vehicle.wear_rr_mm = wear_rr;
  scenario.wheels.output = wheels == "ticks" ? WheelUnit::kTicks : WheelUnit::kRadians;

  // Without --config the batch gets the experiments' ideal-mode wheel noise (no slip to model).
  CalibrationConfig options;
  if (!config.empty())
    options = read_calibration_config(config);
  else
    options.batch =
        experiments::method_options(CalibrationMethod::kBatch, experiments::SimMode::kIdeal).batch;
  options.iterative.decay_exponent_q = q;
  options.iterative.ls_window_samples = window;
  options.common.dr_start = *parse_enum<DeadReckoningStart>(start);
  options.common.reference.mode = *parse_enum<ReferenceMode>(reference);
  if (no_altitude) options.common.use_gnss_altitude = false;

  fmt::print(
      "{}, {} laps, --ideal, wear {}/{} mm, wheels {}, {} seeds; q {}, LS window {}, start {}, "
      "reference {}, grade {}{}\n",
      where, scenario.route.laps, wear_rl, wear_rr, wheels, seeds, q, window, start, reference,
      grade, no_altitude ? " (altitude not used)" : "");
  std::vector<CalibrationMethod> methods;
  for (const std::string& name : method_names)
    methods.push_back(*parse_enum<CalibrationMethod>(name));
  std::vector<Stats> stats(methods.size());
  double crlb_variance = 0.0, crlb_exact_counts_variance = 0.0;
  for (int seed = 1; seed <= seeds; ++seed) {
    scenario.seeds.noise = static_cast<std::uint64_t>(seed);
    const sim::SimulatedDrive drive = sim::simulate(scenario);
    const Log log = simulated_log(drive, true);
    const CramerRaoBound bound =
        experiments::scenario_cramer_rao_bound(scenario, log, drive.true_params);
    const CramerRaoBound exact_counts = experiments::scenario_cramer_rao_bound(
        scenario, log, drive.true_params, experiments::CountModel::kExact);
    crlb_variance += std::pow(bound.rms_sigma_circumference_m(), 2) / seeds;
    crlb_exact_counts_variance += std::pow(exact_counts.rms_sigma_circumference_m(), 2) / seeds;
    for (std::size_t m = 0; m < methods.size(); ++m) {
      options.method = methods[m];
      const auto begin = std::chrono::steady_clock::now();
      const AnyCalibrationSummary summary = calibrate(log, options);
      const CalibrationSummary& result = core(summary);
      stats[m].milliseconds.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin)
              .count());
      stats[m].abs_error_mm.push_back(1e3 * std::abs(result.estimate.circumference_rl_m -
                                                     drive.true_params.circumference_rl_m));
      stats[m].abs_error_mm.push_back(1e3 * std::abs(result.estimate.circumference_rr_m -
                                                     drive.true_params.circumference_rr_m));
      stats[m].mean_position_m.push_back(result.after.mean_position_m);
      stats[m].mean_heading_deg.push_back(result.after.mean_heading_rad * 180 / M_PI);
      stats[m].reported_sigma_mm.push_back(1e3 * result.sigma_rl_m());
    }
  }
  const double crlb_mm = 1e3 * std::sqrt(crlb_variance);
  fmt::print(
      "Cramér–Rao sigma (RMS over seeds and wheels): {:.4f} mm (counts taken as exact: {:.4f} "
      "mm)\n",
      crlb_mm, 1e3 * std::sqrt(crlb_exact_counts_variance));
  fmt::print("{:<10} {:>14} {:>13} {:>8} {:>10} {:>12} {:>17} {:>18} {:>9}\n", "method",
             "mean |err| mm", "max |err| mm", "RMS mm", "RMS/CRLB", "reported mm",
             "mean DR pos err m", "mean DR head err °", "time ms");
  for (std::size_t m = 0; m < methods.size(); ++m) {
    fmt::print(
        "{:<10} {:>14.3f} {:>13.3f} {:>8.3f} {:>10.2f} {:>12.3f} {:>17.2f} {:>18.3f} {:>9.1f}\n",
        method_name(methods[m]), mean(stats[m].abs_error_mm), max_of(stats[m].abs_error_mm),
        rms(stats[m].abs_error_mm), rms(stats[m].abs_error_mm) / crlb_mm,
        mean(stats[m].reported_sigma_mm), mean(stats[m].mean_position_m),
        mean(stats[m].mean_heading_deg), mean(stats[m].milliseconds));
  }
  return 0;
}
