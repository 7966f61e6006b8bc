#pragma once
// A log whose wheels turn as if each rolled a circumference that follows the driving state with
// known tyre coefficients: the truth for the tyre models' tests.

#include <cstddef>
#include <cstdint>

#include "odocal/data/log.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/model/tyre_model.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal::testing {

// A wheel that rolls c f per revolution needs 1/f times the revolutions; f from `truth` in the
// log's own driving state (its accelerometer's included).
inline Log with_wheels_recounted(Log log, const TyreModel& truth, const VehicleBody& body) {
  const auto states = driving_states(log, log.vehicle.nominal_params());
  for (std::size_t k = 0; k < log.wheels.size(); ++k) {
    log.wheels.rev_rl[k] /= tyre_factor(truth, states[k], RearWheel::kLeft, body);
    log.wheels.rev_rr[k] /= tyre_factor(truth, states[k], RearWheel::kRight, body);
  }
  return log;
}

// The same with vehicle.yaml's body.
inline Log with_wheels_recounted(const Log& log, const TyreModel& truth) {
  return with_wheels_recounted(log, truth, log.vehicle.body_geometry());
}

// The ideal built-in circuit under `gnss_sigma_m` of white fixes (0: the scenario's), on noise
// seed `noise_seed` (0: the scenario's), its wheels recounted.
struct RecountedDrive {
  sim::SimulatedDrive drive;
  Log log;
};
inline RecountedDrive ideal_circuit_recounted(const TyreModel& truth, double gnss_sigma_m,
                                              std::uint64_t noise_seed = 0) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  if (gnss_sigma_m > 0.0) scenario.gnss.sigma_m = gnss_sigma_m;
  if (noise_seed > 0) scenario.seeds.noise = noise_seed;
  RecountedDrive result{sim::simulate(scenario), {}};
  result.log = with_wheels_recounted(simulated_log(result.drive), truth);
  return result;
}

}  // namespace odocal::testing
