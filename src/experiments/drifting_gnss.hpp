#pragma once
// A drive whose GNSS drifts while the configuration says otherwise: 5 cm of white noise on a
// Gauss-Markov error, the log without a sigma_m column, and options that claim 0.1 m of white
// noise (the mistake the batch's GNSS noise adaptation is for; bench/honest_sigma.cpp).

#include "odocal/estimation/calibration.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal::experiments {

struct DriftingGnssDrive {
  sim::Scenario scenario;  // the given one with its GNSS made to drift: what was simulated
  sim::SimulatedDrive drive;
  Log log;
  CalibrationOptions claimed;  // 0.1 m of white GNSS noise
};

DriftingGnssDrive drifting_gnss_drive(sim::Scenario scenario, double gauss_markov_sigma_m,
                                      double gauss_markov_tau_s);

}  // namespace odocal::experiments
