#pragma once
// The calibrated parameters in the forms other tools take: an updated vehicle.yaml, the ROS 2
// diff_drive_controller parameters, and back from `odocal calibrate --json`.

#include <filesystem>
#include <optional>

#include "odocal/data/log.hpp"
#include "odocal/estimation/batch_calibration.hpp"

namespace odocal {

// vehicle.yaml with the calibrated circumferences and track width, and the calibrated tyre model
// (none when it is plain: a plain calibration's circumferences replace any earlier model); every
// other key as before.
void write_calibrated_vehicle(const VehicleConfig& nominal, const OdometryParams& calibrated,
                              const std::filesystem::path& path, const TyreModel& tyre = {});

// ROS 2 diff_drive_controller parameters: wheel_separation and wheel_radius from the nominal
// vehicle (the mean of the rear radii), and the multipliers that turn them into the calibrated
// values: left/right_wheel_radius_multiplier, wheel_separation_multiplier. The controller has
// constant radii: a tyre model that is not plain is said in a comment and left out (the
// multipliers are then the circumferences rolling at the reference speed where the calibration
// gives them, else those at rest).
void write_ros2_diff_drive_parameters(const VehicleConfig& nominal,
                                      const OdometryParams& calibrated,
                                      const std::filesystem::path& path, const TyreModel& tyre = {},
                                      const std::optional<ReferenceCircumference>& rolling = {});

// circumference_rl_m, circumference_rr_m and track_width_m of a calibration result JSON; throws
// InputError naming the file and field when one is missing or not a positive number, or when the
// result says it is not usable.
OdometryParams read_calibrated_parameters(const std::filesystem::path& json_path);

// The tyre model of a calibration result JSON: its estimated tyre_* parameters (plain when there
// are none); throws InputError like read_calibrated_parameters.
TyreModel read_calibrated_tyre_model(const std::filesystem::path& json_path);

// Where a calibration result JSON found the GNSS antenna (forward, left of the rear axle's
// centre, m): its lever_arm_x_m and lever_arm_y_m where both were estimated and identified;
// nothing otherwise (held where stated). Throws InputError like read_calibrated_parameters.
std::optional<Eigen::Vector2d> read_calibrated_antenna(const std::filesystem::path& json_path);

}  // namespace odocal
