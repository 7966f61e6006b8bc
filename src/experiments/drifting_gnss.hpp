#pragma once
// A drive whose GNSS drifts while the configuration says otherwise: 5 cm of white noise on a
// Gauss-Markov error, the log without a sigma_m column, and options that claim 0.1 m of white
// noise (the mistake the batch's GNSS noise adaptation is for; bench/honest_sigma.cpp).

#include "odocal/estimation/calibration.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal::experiments {

struct DriftingGnssDrive {
  sim::SimulatedDrive drive;
  Log log;
  CalibrationOptions claimed;  // 0.1 m of white GNSS noise
};

// The scenario's GNSS made to drift so (what drifting_gnss_drive simulates).
sim::Scenario with_drifting_gnss(sim::Scenario scenario, double gauss_markov_sigma_m,
                                 double gauss_markov_tau_s);

DriftingGnssDrive drifting_gnss_drive(sim::Scenario scenario, double gauss_markov_sigma_m,
                                      double gauss_markov_tau_s);

}  // namespace odocal::experiments
