#include "drifting_gnss.hpp"

#include "odocal/io/simulation_writer.hpp"

namespace odocal::experiments {
namespace {

sim::Scenario with_drifting_gnss(sim::Scenario scenario, double gauss_markov_sigma_m,
                                 double gauss_markov_tau_s) {
  scenario.gnss.sigma_m = 0.05;
  scenario.gnss.gauss_markov_sigma_m = gauss_markov_sigma_m;
  scenario.gnss.gauss_markov_tau_s = gauss_markov_tau_s;
  return scenario;
}

}  // namespace

DriftingGnssDrive drifting_gnss_drive(sim::Scenario scenario, double gauss_markov_sigma_m,
                                      double gauss_markov_tau_s) {
  DriftingGnssDrive result{
      with_drifting_gnss(scenario, gauss_markov_sigma_m, gauss_markov_tau_s), {}, {}, {}};
  result.drive = sim::simulate(result.scenario);
  result.log = simulated_log(result.drive);
  result.log.gnss.sigma_m.clear();  // the claimed noise applies
  result.claimed.reference.gnss_sigma_m = 0.1;
  return result;
}

}  // namespace odocal::experiments
