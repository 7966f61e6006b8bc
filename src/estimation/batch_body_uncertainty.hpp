#pragma once
// What vehicle.yaml's body is taken to be uncertain by (1 sigma): a data sheet's numbers for a
// car as it is loaded and tyred on the day (docs/tyre-model.md). The batch moves each by a step
// of it to see what the estimate does (batch_considered_uncertainty.cpp) and names them in its
// verdicts.

#include <fmt/format.h>

#include <string>

#include "odocal/model/tyre_model.hpp"

namespace odocal::batch {

struct BodyUncertainty {
  const char* key;  // vehicle.yaml's
  double VehicleBody::*member;
  double absolute;  // sigma = absolute + relative * value
  double relative;
  bool all_wheel_drive_only = false;  // moves nothing on a car that one axle drives
  double sigma(const VehicleBody& body) const { return absolute + relative * (body.*member); }
  std::string text() const {
    return absolute > 0.0 ? fmt::format("{} +-{:g}", key, absolute)
                          : fmt::format("{} +-{:g} %", key, 100.0 * relative);
  }
};
inline constexpr BodyUncertainty kBodyUncertainties[] = {
    {"rear_axle_load_share", &VehicleBody::rear_axle_load_share, 0.04, 0.0},
    {"cg_height_m", &VehicleBody::cg_height_m, 0.1, 0.0},
    {"rear_roll_share", &VehicleBody::rear_roll_share, 0.1, 0.0},
    {"drag_area_m2", &VehicleBody::drag_area_m2, 0.0, 0.3},
    {"rolling_resistance", &VehicleBody::rolling_resistance, 0.004, 0.0},
    // Dry asphalt to a worn tyre on a dusty road; a tyre's curve from its data (C 1.4-1.9); a
    // brake balance or a torque split from the car's data sheet.
    {"friction", &VehicleBody::friction, 0.15, 0.0},
    {"slip_curve_shape", &VehicleBody::slip_curve_shape, 0.15, 0.0},
    {"brake_rear_share", &VehicleBody::brake_rear_share, 0.05, 0.0},
    // The tyres' cornering stiffness, each axle's on its own (their difference is the car's
    // understeer), and the lateral curve's shape: a tyre's data sheet, which few logs come with.
    {"front_cornering_stiffness", &VehicleBody::front_cornering_stiffness, 0.0, 0.25},
    {"rear_cornering_stiffness", &VehicleBody::rear_cornering_stiffness, 0.0, 0.25},
    {"lateral_curve_shape", &VehicleBody::lateral_curve_shape, 0.15, 0.0},
    {"all_wheel_drive_rear_share", &VehicleBody::all_wheel_drive_rear_share, 0.1, 0.0, true},
};

}  // namespace odocal::batch
