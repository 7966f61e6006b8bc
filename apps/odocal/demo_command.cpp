#include "demo_command.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <memory>

#include "exit_codes.hpp"
#include "number_checks.hpp"
#include "odocal/estimation/iterative_calibration.hpp"
#include "odocal/io/log_reader.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal::cli {
namespace {

struct DemoArgs {
  std::string out_dir = "demo-log";
  double wear_rl_mm = 1.5;
  double wear_rr_mm = 1.0;
  std::uint64_t seed = 1;
};

void run_demo(const DemoArgs& args) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;  // the paper's model assumptions
  scenario.vehicle.wear_rl_mm = args.wear_rl_mm;
  scenario.vehicle.wear_rr_mm = args.wear_rr_mm;
  scenario.seeds.noise = args.seed;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  write_simulated_log(drive, scenario, args.out_dir);
  fmt::print(
      "simulated    {}: {} laps, {:.1f} m, wear RL {} mm / RR {} mm, paper's sensor noise -> "
      "{}\n\n",
      scenario.name, scenario.route.laps, drive.distance_m, args.wear_rl_mm, args.wear_rr_mm,
      args.out_dir);

  LogReadOptions read_options;
  read_options.read_truth = false;
  const IterativeSummary result = calibrate_iterative(read_log(args.out_dir, read_options));
  fmt::print("{}", result.full_report());
  if (!result.usable()) throw NotUsableResult(result.message);

  fmt::print("\n{:<6} {:>12} {:>12} {:>12} {:>10}\n", "", "nominal [m]", "estimate [m]", "true [m]",
             "error [mm]");
  const auto row = [](const char* name, double nominal, double estimate, double truth) {
    fmt::print("{:<6} {:>12.6f} {:>12.6f} {:>12.6f} {:>+10.3f}\n", name, nominal, estimate, truth,
               1e3 * (estimate - truth));
  };
  row("c_RL", result.nominal.circumference_rl_m, result.estimate.circumference_rl_m,
      drive.true_params.circumference_rl_m);
  row("c_RR", result.nominal.circumference_rr_m, result.estimate.circumference_rr_m,
      drive.true_params.circumference_rr_m);
}

}  // namespace

void add_demo_command(CLI::App& app) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* command = app.add_subcommand("demo",
                                         "Simulate the paper's 3-lap circuit with worn rear tyres, "
                                         "calibrate it, compare with the truth");
  command->add_option("--out", args->out_dir, "Where the simulated log goes")
      ->capture_default_str();
  command->add_option("--wear-rl", args->wear_rl_mm, "Rear-left wear, mm of radius")
      ->capture_default_str()
      ->check(finite_in(kTyreWearMm));
  command->add_option("--wear-rr", args->wear_rr_mm, "Rear-right wear, mm of radius")
      ->capture_default_str()
      ->check(finite_in(kTyreWearMm));
  command->add_option("--seed", args->seed, "Noise seed")->capture_default_str();
  command->callback([args] { run_demo(*args); });
}

}  // namespace odocal::cli
