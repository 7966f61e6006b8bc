#include "simulate_command.hpp"

#include <fmt/format.h>

#include <memory>
#include <optional>

#include "number_checks.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal::cli {
namespace {

struct SimulateArgs {
  std::string scenario = "circuit";
  std::string out_dir;
  std::string track_file;
  bool ideal = false;
  std::optional<int> laps;
  std::optional<double> wear_rl_mm;
  std::optional<double> wear_rr_mm;
  std::optional<double> pressure_rl;
  std::optional<double> pressure_rr;
  std::optional<std::string> vehicle_id;
  std::optional<std::uint64_t> noise_seed;
  std::optional<std::uint64_t> trajectory_seed;
  std::optional<double> gnss_sigma_m;
  std::optional<double> gnss_speed_sigma_mps;
  std::optional<std::string> gnss_output;
  std::optional<std::string> gnss_altitude;
  std::optional<std::string> wheel_output;
};

void run_simulate(const SimulateArgs& args) {
  sim::Scenario scenario = load_scenario(args.scenario);
  if (args.ideal) scenario.ideal = true;
  if (!args.track_file.empty()) {
    const double deviation_m = use_track_file(scenario, args.track_file);
    fmt::print("track        {}: closed lap within {:.2f} m of the centreline\n", args.track_file,
               deviation_m);
  }
  if (args.laps) scenario.route.laps = *args.laps;
  if (args.wear_rl_mm) scenario.vehicle.wear_rl_mm = *args.wear_rl_mm;
  if (args.wear_rr_mm) scenario.vehicle.wear_rr_mm = *args.wear_rr_mm;
  if (args.pressure_rl) scenario.vehicle.pressure_rl = *args.pressure_rl;
  if (args.pressure_rr) scenario.vehicle.pressure_rr = *args.pressure_rr;
  if (args.noise_seed) scenario.seeds.noise = *args.noise_seed;
  if (args.trajectory_seed) scenario.seeds.trajectory = *args.trajectory_seed;
  if (args.gnss_sigma_m) scenario.gnss.sigma_m = *args.gnss_sigma_m;
  if (args.gnss_speed_sigma_mps) scenario.gnss.speed_sigma_mps = *args.gnss_speed_sigma_mps;
  if (args.gnss_output) scenario.gnss.output_latlon = *args.gnss_output == "latlon";
  if (args.gnss_altitude) {
    using Altitude = sim::GnssSimConfig::Altitude;
    scenario.gnss.altitude = *args.gnss_altitude == "always"  ? Altitude::kAlways
                             : *args.gnss_altitude == "never" ? Altitude::kNever
                                                              : Altitude::kAuto;
  }
  if (args.wheel_output) scenario.wheels.output = *parse_enum<WheelUnit>(*args.wheel_output);

  sim::SimulatedDrive drive = sim::simulate(scenario);
  drive.nominal_vehicle.vehicle_id = args.vehicle_id;
  write_simulated_log(drive, scenario, args.out_dir);
  fmt::print("simulated    {} ({}), {} lap(s): {:.1f} m in {:.1f} s\n", scenario.name,
             scenario.ideal ? "ideal" : "realistic", scenario.route.laps, drive.distance_m,
             drive.wheel_t_s.back());
  fmt::print("true wheels  c_RL {:.6f} m, c_RR {:.6f} m (nominal {:.6f} m), t_R {:.4f} m\n",
             drive.true_params.circumference_rl_m, drive.true_params.circumference_rr_m,
             drive.nominal_vehicle.circumference_rl_m, drive.true_params.track_width_m);
  fmt::print("written      {} ({} wheel samples, {} GNSS fixes)\n", args.out_dir,
             drive.wheel_t_s.size(), drive.gnss_t_s.size());
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* command =
      app.add_subcommand("simulate", "Simulate a drive and its sensors into a log directory");
  command
      ->add_option("--scenario", args->scenario,
                   "Built-in scenario (circuit, parking, urban, robot) or a scenario YAML file")
      ->capture_default_str();
  command->add_option("--out", args->out_dir, "Output log directory")->required();
  command->add_option("--track", args->track_file,
                      "Closed centreline CSV (TUMFTM format) replacing the scenario's route");
  command->add_flag("--ideal", args->ideal,
                    "Kinematic motion, no slip, constant radius: the paper's model assumptions");
  command->add_option("--laps", args->laps, "Laps of the route")->check(CLI::Range(1, 1000));
  command->add_option("--wear-rl", args->wear_rl_mm, "Rear-left tyre wear: radius lost, mm")
      ->check(finite_in(kTyreWearMm));
  command->add_option("--wear-rr", args->wear_rr_mm, "Rear-right tyre wear: radius lost, mm")
      ->check(finite_in(kTyreWearMm));
  command
      ->add_option("--pressure-rl", args->pressure_rl,
                   "Rear-left inflation relative to nominal (0.75: 25 % low)")
      ->check(finite_in(kTyrePressure));
  command
      ->add_option("--pressure-rr", args->pressure_rr,
                   "Rear-right inflation relative to nominal (0.75: 25 % low)")
      ->check(finite_in(kTyrePressure));
  command->add_option("--vehicle-id", args->vehicle_id,
                      "vehicle_id written to vehicle.yaml (a fleet's vehicle)");
  command->add_option("--seed", args->noise_seed, "Noise seed (sensor errors)");
  command->add_option("--trajectory-seed", args->trajectory_seed,
                      "Trajectory seed (driver variation)");
  command->add_option("--gnss-sigma", args->gnss_sigma_m, "GNSS white noise per axis, m")
      ->check(finite_in(0.0, 1e3));
  command
      ->add_option("--gnss-speed-sigma", args->gnss_speed_sigma_mps,
                   "Doppler speed column speed_mps with this white noise, m/s (0: exact); the "
                   "scenario's otherwise (none built in)")
      ->check(finite_in(0.0, 10.0));
  command->add_option("--gnss-output", args->gnss_output, "GNSS as local x,y or lat,lon")
      ->check(CLI::IsMember({"local", "latlon"}));
  command
      ->add_option("--gnss-altitude", args->gnss_altitude,
                   "GNSS alt column: auto (on hills only), always or never")
      ->check(CLI::IsMember({"auto", "always", "never"}));
  command->add_option("--wheel-output", args->wheel_output, "Wheel columns' unit")
      ->check(CLI::IsMember(enum_name_list<WheelUnit>()));
  command->callback([args] { run_simulate(*args); });
}

}  // namespace odocal::cli
