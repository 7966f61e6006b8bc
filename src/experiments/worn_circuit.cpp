#include "worn_circuit.hpp"

#include "odocal/io/scenario_io.hpp"

namespace odocal::experiments {

sim::Scenario worn_ideal_circuit(int laps, std::uint64_t noise_seed) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  scenario.route.laps = laps;
  scenario.vehicle.wear_rl_mm = 1.5;
  scenario.vehicle.wear_rr_mm = 1.0;
  scenario.seeds.noise = noise_seed;
  return scenario;
}

}  // namespace odocal::experiments
