#include "hilly_urban.hpp"

#include "odocal/io/scenario_io.hpp"

namespace odocal::testing {

sim::Scenario hilly_urban(sim::Drivetrain drivetrain) {
  sim::Scenario scenario = load_scenario("urban");
  scenario.route.laps = 3;
  scenario.route.terrain.max_grade = 0.06;
  scenario.seeds.noise = 3;
  scenario.dynamics.drivetrain = drivetrain;
  return scenario;
}

}  // namespace odocal::testing
