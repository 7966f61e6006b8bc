#pragma once
// A drive whose GNSS drifts while the configuration says otherwise: 5 cm of white noise on a
// Gauss-Markov error, the log without a sigma_m column, and options that claim 0.1 m of white
// noise (the mistake the batch's GNSS noise adaptation is for; bench/honest_sigma.cpp).

#include <cstdint>

#include "odocal/estimation/calibration.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal::experiments {

// The built-in circuit, ideal, the rear tyres worn 1.5 / 1.0 mm: the honest-sigma bench's drive.
sim::Scenario worn_ideal_circuit(int laps, std::uint64_t noise_seed);

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
