#pragma once
// The realistic urban drive on hills of up to 6 %, 3 laps: the drive on which the tests check what
// climbing does to the tyres (the grade in the verdict, the slope's force in the tyre model).

#include "odocal/sim/scenario.hpp"

namespace odocal::testing {

sim::Scenario hilly_urban(sim::Drivetrain drivetrain = sim::Drivetrain::kRear);

}  // namespace odocal::testing
