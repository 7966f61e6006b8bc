#pragma once
// A drive the tests and the honest-sigma bench calibrate: the built-in circuit, ideal (the
// paper's model assumptions), its rear tyres worn 1.5 / 1.0 mm of radius.

#include <cstdint>

#include "odocal/sim/scenario.hpp"

namespace odocal::experiments {

sim::Scenario worn_ideal_circuit(int laps, std::uint64_t noise_seed);

}  // namespace odocal::experiments
