#pragma once
// Simulates a drive and its sensors. Returns raw sensor columns as a logger would write them
// (cumulative ticks, lat/lon, ...) plus the truth.

#include <array>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/model/tyre_model.hpp"
#include "odocal/sim/scenario.hpp"

namespace odocal::sim {

struct SimulatedDrive {
  VehicleConfig nominal_vehicle;  // what vehicle.yaml says (unworn tyres)
  OdometryParams true_params;     // circumferences after wear, true track width
  // Each rear wheel's effective circumference driving straight at a steady speed (the static
  // one in ideal mode): a tyre model's reference circumference (BatchOptions::reference_speed_mps).
  double steady_rolling_speed_mps = kDefaultReferenceSpeedMps;
  std::array<double, 2> steady_rolling_circumference_m{};
  // wheels.csv: raw values in `wheel_unit` (ticks cumulative and wrapped, rad cumulative, ...)
  std::vector<double> wheel_t_s, wheel_rl, wheel_rr;
  WheelUnit wheel_unit{WheelUnit::kTicks};
  std::vector<double> wheel_drive_force_n;  // its drive_force_n column (N); empty: none
  // gnss.csv: x/y in metres, or lat/lon in degrees when `gnss_latlon`
  std::vector<double> gnss_t_s, gnss_a, gnss_b;
  // gnss.csv's alt column (m, with its noise): local up, or ellipsoidal height with lat/lon; empty
  // on flat terrain.
  std::vector<double> gnss_alt;
  std::vector<double> gnss_speed_mps;  // its speed_mps column (horizontal); empty: none
  bool gnss_latlon{};
  double gnss_sigma_m{};
  ImuStream imu;
  HeadingStream heading;
  PoseStream truth;     // reference point at the wheel rate
  double distance_m{};  // of the rear-axle midpoint
};

// The path of the scenario's route (all laps).
Path route_path(const Scenario& scenario);

// Ideal mode: the exact path and the paper's model assumptions; otherwise the dynamic vehicle.
SimulatedDrive simulate(const Scenario& scenario);

}  // namespace odocal::sim
