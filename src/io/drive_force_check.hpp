#pragma once
// wheels.csv's drive_force_n against the motion that the wheels show: a force in another unit,
// with its sign turned or on another clock is an input mistake that a tyre model would otherwise
// fit as slip.

#include "odocal/data/log.hpp"
#include "odocal/io/csv_table.hpp"

namespace odocal::detail {

// Throws InputError naming the column where a value is beyond 3 g for the body's mass, or where
// the force over the mass follows the wheels' acceleration with drag and rolling resistance
// (1 s means) at a gain outside [0.5, 2] or hardly at all (a log with too little acceleration to
// tell, fewer than 20 s of driving or its acceleration spread below 0.3 m/s^2, is not judged so),
// or where it gives less than a quarter of the braking that the wheels show (a drive torque
// without the brakes').
void check_drive_force(const CsvTable& table, const WheelStream& wheels,
                       const VehicleConfig& vehicle);

}  // namespace odocal::detail
