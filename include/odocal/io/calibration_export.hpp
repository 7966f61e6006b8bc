#pragma once
// The calibrated parameters in the forms other tools take: an updated vehicle.yaml, the ROS 2
// diff_drive_controller parameters, and back from `odocal calibrate --json`.

#include <filesystem>

#include "odocal/data/log.hpp"

namespace odocal {

// vehicle.yaml with the calibrated circumferences and track width; every other key as before.
void write_calibrated_vehicle(const VehicleConfig& nominal, const OdometryParams& calibrated,
                              const std::filesystem::path& path);

// ROS 2 diff_drive_controller parameters: wheel_separation and wheel_radius from the nominal
// vehicle (the mean of the rear radii), and the multipliers that turn them into the calibrated
// values: left/right_wheel_radius_multiplier, wheel_separation_multiplier.
void write_ros2_diff_drive_parameters(const VehicleConfig& nominal,
                                      const OdometryParams& calibrated,
                                      const std::filesystem::path& path);

// circumference_rl_m, circumference_rr_m and track_width_m of a calibration result JSON; throws
// InputError naming the file and field when one is missing or not a positive number, or when the
// result says it is not usable.
OdometryParams read_calibrated_parameters(const std::filesystem::path& json_path);

}  // namespace odocal
