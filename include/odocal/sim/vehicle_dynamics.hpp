#pragma once
// The realistic vehicle: a single-track (bicycle) model with magic-formula lateral tyre forces,
// longitudinal and lateral load transfer, rear-, front- or all-wheel drive and a front/rear
// brake split,
// aerodynamic drag and rolling resistance, integrated by RK4 at a fixed step, steered along the
// path and driven along the speed profile by controllers. Each rear wheel turns at its own
// contact-point speed (vx -+ r t_R / 2) times (1 + longitudinal slip) over an effective rolling
// radius that depends on its vertical load. docs/simulator.md has the equations and defaults.

#include <array>
#include <functional>
#include <memory>

#include "odocal/model/tyre_model.hpp"
#include "odocal/sim/motion_truth.hpp"
#include "odocal/sim/path.hpp"
#include "odocal/sim/speed_profile.hpp"

namespace odocal::sim {

using odocal::Drivetrain;

struct VehicleDynamicsConfig {
  // Effects, each switchable alone (docs/simulator.md measures each one's drift).
  bool dynamic_lateral = true;        // tyre side slip; false: kinematic bicycle (no side slip)
  bool longitudinal_slip = true;      // drive/brake slip of the rear wheels
  bool load_dependent_radius = true;  // rolling radius shrinks with vertical load
  bool load_transfer = true;          // longitudinal and lateral load transfer

  double mass_kg = 1500.0;
  double yaw_inertia_kgm2 = 2600.0;
  double cg_to_front_axle_m = 1.25;  // a; b = wheelbase - a
  double cg_height_m = 0.55;
  double front_roll_share = 0.55;  // share of the lateral load transfer taken by the front axle
  double friction = 1.0;           // mu
  double cornering_stiffness_per_load_front = 16.0;  // C_alpha / F_z, 1/rad
  double cornering_stiffness_per_load_rear = 19.0;
  double lateral_shape = 1.3;             // magic formula C (lateral)
  double slip_stiffness_per_load = 20.0;  // C_kappa / F_z (longitudinal)
  double longitudinal_shape = 1.65;       // magic formula C (longitudinal)
  double drag_area_m2 = 0.7;              // c_d A
  double air_density_kgpm3 = 1.2;
  double rolling_resistance = 0.012;
  double brake_front_share = 0.65;
  Drivetrain drivetrain = Drivetrain::kRear;
  double drive_front_share_all = 0.4;  // all-wheel drive: the front axle's share of the drive
  // Effective rolling radius change per N of load: radial tyres keep it nearly load-independent
  // (stiff belt), ~0.4 mm per kN; a third of the deflection (1.3e-6) would be a bias-ply tyre.
  double radius_load_sensitivity_m_per_n = 4e-7;
  // Centrifugal growth of the rolling radius per (m/s)^2 of the wheel's speed (the Magic
  // Formula's q_V1 term on the free radius); 2e-6 is 0.125 % at 25 m/s.
  // Off by default: the physical terms have no such term yet (docs/tyre-model.md, "On drives
  // odocal did not simulate").
  double radius_speed_growth_s2pm2 = 0.0;
  double max_steer_rad = 0.6;
  double preview_distance_m = 6.0;   // path-following gains: critically damped over this distance
  double speed_gain_1ps = 1.5;       // speed-error feedback
  double position_gain_1ps2 = 0.5;   // progress-error feedback
  double kinematic_below_mps = 3.0;  // slip angles are singular at standstill
  double step_hz = 1000.0;
  double control_hz = 100.0;
  // The drive's and the brakes' force follow the driver's command through a first-order lag of
  // this time constant, s: an engine's torque and a brake's pressure build over a tenth of a
  // second, never in a step. 0: at once, a step at every control tick (odocal before
  // 2026-12-05, whose sensors then sampled a force that jumps exactly at their sample times;
  // docs/simulator.md, "The actuators' lag").
  double actuator_time_constant_s = 0.1;
};

struct StaticRearRadii {
  double rl_m;  // effective rolling radius under static load (what truth.yaml calls true)
  double rr_m;
  double pressure_rl = 1.0;  // relative inflation: the load sensitivity grows as 1 / pressure
  double pressure_rr = 1.0;
};

// Static load on one rear wheel, N.
double static_rear_wheel_load_n(const VehicleDynamicsConfig& config, double wheelbase_m);

// Each rear wheel's effective rolling radius driving straight at a steady speed (its drive slip
// against drag and rolling resistance in it): what a constant radius should be in gentle driving.
std::array<double, 2> steady_rolling_radii_m(const VehicleDynamicsConfig& config,
                                             double wheelbase_m, double track_width_m,
                                             const StaticRearRadii& radii, double speed_mps);

// Simulates the drive; the wheel radii at static load are given (nominal minus wear). `grade`:
// the road's dz/ds at a distance along the path (empty: flat), which the drive force climbs.
std::unique_ptr<MotionTruth> simulate_vehicle_dynamics(
    const Path& path, const SpeedProfile& profile, const VehicleDynamicsConfig& config,
    double wheelbase_m, double track_width_m, const StaticRearRadii& radii,
    const std::function<double(double)>& grade = {});

}  // namespace odocal::sim
