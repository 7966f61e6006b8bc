#pragma once
// Simulated drives that several test files share: a car whose body vehicle.yaml does not describe,
// and laps whose wheels run on another track than vehicle.yaml states.

#include <cstdint>

#include "odocal/io/scenario_io.hpp"
#include "odocal/sim/scenario.hpp"

namespace odocal::testing {

// Lower and heavier than vehicle.yaml's body, with softer, more load-sensitive tyres, less
// rolling resistance and more of the roll stiffness at the front (bench/tyre_model_bench.py's
// "low-heavy" car).
inline sim::Scenario with_low_heavy_body(sim::Scenario scenario) {
  scenario.dynamics.cg_height_m = 0.45;
  scenario.dynamics.mass_kg = 1800.0;
  scenario.dynamics.slip_stiffness_per_load = 14.0;
  scenario.dynamics.radius_load_sensitivity_m_per_n = 6e-7;
  scenario.dynamics.rolling_resistance = 0.009;
  scenario.dynamics.front_roll_share = 0.6;
  return scenario;
}

// One ideal lap of the built-in circuit, the wheels on an effective track of `effective_track_m`
// (0: the stated one).
inline sim::Scenario ideal_lap_on_track(double effective_track_m) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  scenario.route.laps = 1;
  scenario.vehicle.effective_track_width_m = effective_track_m;
  return scenario;
}

// One lap of the built-in circuit, realistic (rear-driven, its tyres slipping), noise and
// trajectory seed `seed`, the wheels on an effective track of `effective_track_m`.
inline sim::Scenario realistic_lap_on_track(double effective_track_m, std::uint64_t seed) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.route.laps = 1;
  scenario.seeds.noise = seed;
  scenario.seeds.trajectory = seed;
  scenario.vehicle.effective_track_width_m = effective_track_m;
  return scenario;
}

// One lap (1 km) of the built-in urban drive, realistic, on a `drivetrain` car, noise and
// trajectory seed `seed`.
inline sim::Scenario realistic_urban_lap(sim::Drivetrain drivetrain, std::uint64_t seed) {
  sim::Scenario scenario = load_scenario("urban");
  scenario.dynamics.drivetrain = drivetrain;
  scenario.route.laps = 1;
  scenario.seeds = {seed, seed};
  return scenario;
}

}  // namespace odocal::testing
