#pragma once
// Everything a simulation run needs: route, driver, vehicle, sensors and seeds. Defaults are the
// paper's section 5 (50 Hz everywhere, sigma_GPS 3 m, sigma_acc 0.2 m/s^2, sigma_yaw-rate
// 0.02 rad/s, sigma_heading 0.15 rad) and its tyre radius 312.6 mm. Documented knob by knob in
// config/scenarios/*.yaml and docs/simulator.md.

#include <cstdint>
#include <string>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/sim/path.hpp"
#include "odocal/sim/speed_profile.hpp"
#include "odocal/sim/vehicle_dynamics.hpp"

namespace odocal::sim {

struct RouteSegment {
  PathSegment geometry;
  double stop_dwell_s{};  // > 0: stop at the end of this segment for that long
};

// Hills along the road: altitude z(s) = A sin(2 pi s / lambda) over the distance s driven, with
// the amplitude A chosen for the maximum grade and lambda rounded so that every lap closes; no
// cross slope. 0: flat.
struct Terrain {
  double max_grade = 0.0;  // dz/ds, e.g. 0.06 for 6 %
  double wavelength_m = 500.0;
};

struct Route {
  std::vector<RouteSegment> segments;
  int repeat = 1;  // the segment list is driven this many times per lap
  int laps = 1;
  Pose2 start = Pose2::Zero();
  Terrain terrain;
};

struct VehicleSimConfig {
  double track_width_m = 1.6;  // the geometric rear track: what vehicle.yaml states
  // The track the wheels' speed difference implies in a turn (a skid-steer robot's wheels slide
  // sideways, so its effective track is wider than the geometric one); 0: track_width_m.
  double effective_track_width_m = 0.0;
  double wheelbase_m = 2.7;
  double tyre_radius_m = 0.3126;  // nominal, unloaded (paper section 1)
  double wear_rl_mm = 0.0;        // radius lost to tyre wear, per rear wheel
  double wear_rr_mm = 0.0;
  // Inflation pressure per rear wheel relative to the nominal one (0.75: 25 % under-inflated).
  // The tyre's vertical stiffness scales with it, so its deflection under load, and the rolling
  // radius lost to that deflection, grow as 1 / pressure.
  double pressure_rl = 1.0;
  double pressure_rr = 1.0;
};

struct Outage {
  double start_s{};  // seconds after the log's first sample
  double duration_s{};
};

struct GnssSimConfig {
  double rate_hz = 50.0;
  double sigma_m = 3.0;  // white noise per axis
  double gauss_markov_sigma_m = 0.0;
  double gauss_markov_tau_s = 60.0;
  double outlier_rate = 0.0;  // probability per fix
  double outlier_min_m = 20.0;
  double outlier_max_m = 50.0;
  double latency_s = 0.0;  // a fix stamped t reports the position at t - latency
  // The antenna ahead of and left of the rear axle's centre: the fixes and the Doppler speed are
  // that point's (a car's antenna is seldom over the axle; the batch's detect_mounting).
  double lever_arm_x_m = 0.0, lever_arm_y_m = 0.0;
  // Whether vehicle.yaml states that place (gnss_x_m, gnss_y_m), as an owner who measured the
  // mounting does; else the calibration is left to find it.
  bool lever_arm_stated = false;
  // Altitude noise (white, m) of the alt column, written when the terrain is not flat; negative:
  // 1.5 x sigma_m (GNSS altitude is worse than its horizontal position).
  double altitude_sigma_m = -1.0;
  // Doppler speed over ground (white noise, m/s) of gnss.csv's speed_mps column, drawn from a
  // generator of its own (the positions keep their noise); negative: no column.
  double speed_sigma_mps = -1.0;
  // Whether gnss.csv has an alt column: auto writes it on hills only (flat logs keep their noise
  // sequence); always is a receiver that reports its altitude on a flat road too.
  enum class Altitude { kAuto, kAlways, kNever } altitude = Altitude::kAuto;
  std::vector<Outage> outages;
  bool output_latlon = false;
  GeodeticOrigin origin{49.3278, 8.5656, 103.0};  // Hockenheimring
};

struct ImuSimConfig {
  double rate_hz = 50.0;
  double acc_sigma_mps2 = 0.2;
  double yaw_rate_sigma_radps = 0.02;
  double gyro_bias_radps = 0.0;
  // Where the IMU is mounted, forward and left of the point whose motion the mode's IMU reads
  // (realistic: the centre of gravity; ideal: the rear axle), m.
  double mount_x_m = 0.0, mount_y_m = 0.0;
};

struct HeadingSimConfig {
  double rate_hz = 50.0;
  double sigma_rad = 0.15;
  double bias_rad = 0.0;
};

struct WheelSimConfig {
  double rate_hz = 50.0;
  WheelUnit output = WheelUnit::kTicks;
  int ticks_per_rev = 96;
  int counter_bits = 16;  // 0: the counter never wraps
  // Where each counter starts between two ticks, in ticks [0, 1); negative: drawn per wheel from
  // the noise seed, as a real encoder is found at power-up.
  double start_phase = -1.0;
  // Zero-rate bias of angular-rate wheel sensors (outputs radps and mps), rad/s of wheel rate.
  double rate_bias_rl_radps = 0.0;
  double rate_bias_rr_radps = 0.0;
  // wheels.csv's drive_force_n column, the tyres' total longitudinal force as a car's bus gives
  // it (engine torque through the gears over the radius, less the brakes'): its white noise (N)
  // and its scale (the torque map's and the radius's error); negative sigma: no column.
  double drive_force_sigma_n = -1.0;
  double drive_force_scale = 1.0;
};

struct Seeds {
  std::uint64_t trajectory = 1;  // driver variation
  std::uint64_t noise = 1;       // every sensor error
};

struct Scenario {
  std::string name;
  Route route;
  DriverLimits driver;
  double speed_variation = 0.0;  // each segment's speed cap scaled by U[1 - v, 1] (trajectory seed)
  VehicleSimConfig vehicle;
  bool ideal = false;  // true: exact path, no slip, constant radius (the paper's model assumptions)
  VehicleDynamicsConfig dynamics;  // the realistic vehicle (ideal = false)
  GnssSimConfig gnss;
  ImuSimConfig imu;
  HeadingSimConfig heading;
  WheelSimConfig wheels;
  Seeds seeds;
};

}  // namespace odocal::sim
