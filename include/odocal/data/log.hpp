#pragma once
// The neutral in-memory log: what every reader/importer produces and every estimator consumes.
// Streams keep their own time bases (seconds on one shared clock, strictly increasing).
// Frames: local ENU world (x east, y north), body x forward / y left / z up, yaw CCW from +x.

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "odocal/model/odometry_model.hpp"
#include "odocal/model/tyre_model.hpp"
#include "odocal/options/enum_names.hpp"

namespace odocal {

// Nominal vehicle description (vehicle.yaml): the starting guess of the calibration.
struct VehicleConfig {
  double track_width_m{};
  double circumference_rl_m{};
  double circumference_rr_m{};
  std::optional<double> ticks_per_rev;
  std::optional<int> counter_bits;
  std::optional<double> wheelbase_m;
  std::optional<double> circumference_fl_m;
  std::optional<double> circumference_fr_m;
  std::optional<std::string> vehicle_id;  // which vehicle of a fleet (letters, digits, . _ -)
  // Where imu.csv's sensor sits, forward and left of the rear axle's centre (m; vehicle.yaml's
  // imu_x_m, imu_y_m). Layer 1 takes its readings to the axle and the physical tyre terms to the
  // centre of gravity: one ahead of a point reads each turn's -w^2 x and dw/dt x beside the
  // point's. Unstated: layer 1 takes it at the axle, the tyre terms at the centre of gravity.
  std::optional<Eigen::Vector2d> imu_position_m;
  // Where the GNSS antenna sits, forward and left of the rear axle's centre (m; vehicle.yaml's
  // gnss_x_m, gnss_y_m): the fixes and the Doppler speed are that point's. Layer 1 measures the
  // axle through it, and the batch holds its lever arm there (or starts there, when it estimates
  // it). Unstated: the fixes are taken as the axle's, and the batch's options say.
  std::optional<Eigen::Vector2d> gnss_position_m;
  // A calibrated condition-dependent circumference (docs/tyre-model.md); dead reckoning applies
  // it. Absent: the plain model.
  std::optional<TyreModel> tyre_model;
  // What the tyre model's physical terms are computed with (vehicle.yaml's body); its wheelbase
  // and track are wheelbase_m (when given) and track_width_m, set by body_geometry().
  VehicleBody body;

  OdometryParams nominal_params() const {
    return {circumference_rl_m, circumference_rr_m, track_width_m};
  }
  // The body with this vehicle's wheelbase (when stated), rear track and IMU's place.
  VehicleBody body_geometry() const {
    VehicleBody geometry = body;
    geometry.wheelbase_m = wheelbase_m.value_or(body.wheelbase_m);
    geometry.track_width_m = track_width_m;
    geometry.imu_position_m = imu_position_m;
    return geometry;
  }
};

// How the wheel columns of wheels.csv were given. The name is the suffix of its wheels.csv
// columns ("ticks", "rad", "radps", "mps").
enum class WheelUnit { kTicks, kRadians, kRadiansPerSecond, kMetresPerSecond };
template <>
struct EnumNames<WheelUnit> {
  static constexpr std::array<EnumName<WheelUnit>, 4> kTable{
      {{WheelUnit::kTicks, "ticks"},
       {WheelUnit::kRadians, "rad"},
       {WheelUnit::kRadiansPerSecond, "radps"},
       {WheelUnit::kMetresPerSecond, "mps"}}};
};

// Wheel revolution increments on the wheel time base (eq. 2): rev_*[k] is the number of
// revolutions between t_s[k-1] and t_s[k]; rev_*[0] = 0.
struct WheelStream {
  std::vector<double> t_s;
  std::vector<double> rev_rl;
  std::vector<double> rev_rr;
  std::vector<double> rev_fl;  // empty when the log has no front wheels
  std::vector<double> rev_fr;
  WheelUnit unit_rear{WheelUnit::kTicks};
  // 1 where sample k's increment spans a gap in the stream: the motion there is unknown and the
  // odometry chain breaks (its increment is zero). Empty: no break. Set by preprocessing
  // (odocal/estimation/wheel_gaps.hpp), never by the readers.
  std::vector<std::uint8_t> chain_break;
  // The rear axle's side slip angle over sample k's increment (rad, left of the heading
  // positive), from a tyre model (driving_state.hpp's with_tyre_model); empty: none, as in
  // eqs. 1-2. Never read from a log file.
  std::vector<float> side_slip_rad;
  // The road's grade (dz/ds) under sample k's increment, from the GNSS altitude (road_grade.hpp's
  // projection, which made the increments horizontal); empty: not known. Rows of a block of a
  // long log that had too little altitude for a fit read NaN: not known, and not projected.
  // Never read from a log file.
  std::vector<float> grade;
  // The tyres' total longitudinal force at sample k (N, forward positive: the drive's at the
  // wheels less the brakes'), where the log gives it (wheels.csv's drive_force_n: engine torque
  // through the gears over the wheel radius, from the car's bus); empty: not given. The tyre
  // model's physical terms take their force from it instead of the accelerometer.
  std::vector<double> drive_force_n;

  std::size_t size() const { return t_s.size(); }
  WheelIncrement increment(std::size_t k) const { return {rev_rl[k], rev_rr[k]}; }
  double side_slip(std::size_t k) const { return side_slip_rad.empty() ? 0.0 : side_slip_rad[k]; }
  bool breaks_at(std::size_t k) const { return !chain_break.empty() && chain_break[k] != 0; }
};

struct GeodeticOrigin {
  double latitude_deg{};
  double longitude_deg{};
  double altitude_m{};
};

// GNSS fixes in local ENU metres. Optional columns are empty when absent.
struct GnssStream {
  std::vector<double> t_s;
  std::vector<double> x_m;
  std::vector<double> y_m;
  std::vector<double> altitude_m;
  std::vector<double> sigma_m;           // horizontal 1-sigma
  std::vector<double> speed_mps;         // Doppler speed over ground
  std::optional<GeodeticOrigin> origin;  // set when the file was lat/lon

  std::size_t size() const { return t_s.size(); }
};

// Body-frame IMU: forward/left accelerations and yaw rate (CCW positive).
struct ImuStream {
  std::vector<double> t_s;
  std::vector<double> ax_mps2;
  std::vector<double> ay_mps2;
  std::vector<double> wz_radps;

  std::size_t size() const { return t_s.size(); }
};

// Absolute heading (e.g. magnetic), radians CCW from +x, wrapped to (-pi, pi].
struct HeadingStream {
  std::vector<double> t_s;
  std::vector<double> heading_rad;

  std::size_t size() const { return t_s.size(); }
};

// Timed poses of the reference point (truth.csv; also trajectories).
struct PoseStream {
  std::vector<double> t_s;
  std::vector<Pose2> pose;

  std::size_t size() const { return t_s.size(); }
};

struct Log {
  std::string source;  // directory it was read from, for messages
  VehicleConfig vehicle;
  WheelStream wheels;
  GnssStream gnss;
  std::optional<ImuStream> imu;
  std::optional<HeadingStream> heading;
  std::optional<PoseStream> truth;  // evaluation only: estimators must never read it
};

// Sigma of one cumulative count's quantisation, revolutions: 1/sqrt(12) tick for a counter that
// floors; 0 when the log carries wheel angles or speeds.
inline double encoder_quantisation_sigma_rev(const Log& log) {
  if (log.wheels.unit_rear != WheelUnit::kTicks || !log.vehicle.ticks_per_rev) return 0.0;
  return 1.0 / *log.vehicle.ticks_per_rev / std::sqrt(12.0);
}

}  // namespace odocal
