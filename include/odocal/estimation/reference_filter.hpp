#pragma once
// Layer 1 of the paper (section 3.1): a GNSS/IMU fusion Kalman filter (p'' = a, after Caron et
// al. 2006) that turns GNSS positions, body accelerations, yaw rate and absolute heading into a
// reference pose on the wheel time base. No wheel data enters this layer.
//
// State [x, y, vx, vy, yaw, accelerometer biases x and y, gyro bias]. Prediction integrates the
// body acceleration rotated into the world frame and the yaw rate (each step at the IMU's reading
// at its middle, linear between samples; taken to the rear axle from where vehicle.yaml mounts the
// IMU); GNSS updates x, y; heading updates yaw (wrapped innovation). Without imu.csv the
// prediction is constant velocity with acceleration noise. At each GNSS fix, driving nearly
// straight, the rear axle's velocity across its heading is held to zero, within the side slip a
// car's tyres may have there (the non-holonomic constraint: it ties yaw to the velocity's
// course, velocity to yaw); at the fixes where it does not apply and there is no
// heading.csv, yaw is corrected by the GNSS course when moving instead. GNSS Doppler speed
// (speed_mps), when the file has it, updates the speed |v|: it fixes the along-track scale of the
// reference far better than position differences of noisy fixes.

#include <array>
#include <span>
#include <string>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/options/option_fields.hpp"

namespace odocal {

enum class ReferenceMode { kFilter, kSmoother };  // smoother: Rauch-Tung-Striebel, off-line
template <>
struct EnumNames<ReferenceMode> {
  static constexpr std::array<EnumName<ReferenceMode>, 2> kTable{
      {{ReferenceMode::kFilter, "filter"}, {ReferenceMode::kSmoother, "smoother"}}};
};

struct ReferenceOptions {
  ReferenceMode mode = ReferenceMode::kFilter;  // the paper's filter
  double gnss_sigma_m = 3.0;                    // used when gnss.csv has no sigma_m
  double heading_sigma_rad = 0.15;
  double acc_sigma_mps2 = 0.2;         // IMU acceleration noise per sample
  double yaw_rate_sigma_radps = 0.02;  // IMU yaw-rate noise per sample
  // Extra random walk for what the IMU model misses (vertical dynamics, misalignment, no IMU).
  double acc_random_walk_mps2 = 0.5;    // m/s^2 per sqrt(s)
  double yaw_random_walk_radps = 0.01;  // rad/s per sqrt(s)
  // Without imu.csv: white acceleration and yaw-rate spectral densities of the constant-velocity
  // model (m^2/s^3, rad^2/s), enough for ~7 m/s^2 and ~0.5 rad/s changing within a second.
  double no_imu_acc_psd = 25.0;
  double no_imu_yaw_rate_psd = 0.25;
  // The rear axle's velocity across its heading beyond its side slip, 1-sigma per GNSS
  // fix, at or above the speed and below the turn given; 0: off (the paper's layer 1). Where it
  // does not apply and there is no heading.csv, the GNSS course corrects yaw.
  double lateral_velocity_sigma_mps = 0.05;
  double lateral_velocity_min_speed_mps = 5.0;
  double lateral_velocity_max_turn_radps = 0.05;   // the gyro's, less its bias
  double lateral_velocity_max_lateral_mps2 = 0.2;  // v times that turn
  double course_min_speed_mps = 3.0;  // GNSS-course pseudo-heading only above this speed
  double course_sigma_rad = 0.1;
  double gnss_gate_chi2 = 0.0;              // > 0: reject GNSS fixes whose NIS exceeds this (2 dof)
  double acc_bias_sigma_mps2 = 0.5;         // initial accelerometer bias (x, y) 1-sigma
  double gyro_bias_sigma_radps = 0.01;      // initial gyro bias 1-sigma
  double acc_bias_random_walk_mps2 = 0.01;  // per sqrt(s)
  double gyro_bias_random_walk_radps = 1e-4;  // per sqrt(s)
  bool use_gnss_speed = true;  // gnss.csv speed_mps (Doppler) updates |v| when present
  double gnss_speed_sigma_mps = 0.1;
  double gnss_speed_min_mps = 1.0;  // below this the speed direction is undefined

  static OptionTable<ReferenceOptions> fields();  // keys, units, ranges, docs
  std::string validate() const;                   // empty when valid
};

// The reference on the wheel time base: poses[i] belongs to wheel sample first_wheel_index + i,
// one pose per wheel sample from there on. Its times are the wheels' (t_s), not copied: 8 bytes
// per wheel sample, 28 MB on a 10-hour drive at 100 Hz.
struct ReferenceTrajectory {
  std::size_t first_wheel_index{};
  std::vector<Pose2> poses;  // yaw continuous (unwrapped)
  // Of [x, y, yaw] per pose; empty unless asked for (ReferenceCovariance::kKeep): no estimator
  // needs it, and it is 72 bytes per wheel sample.
  std::vector<Eigen::Matrix3d> covariance;
  std::size_t gnss_used{};
  std::size_t gnss_rejected{};
  std::string heading_source;  // "heading.csv" or "GNSS course"

  // The poses' times, from the wheel stream the reference was computed on.
  std::span<const double> times(const WheelStream& wheels) const {
    return std::span<const double>(wheels.t_s).subspan(first_wheel_index, poses.size());
  }
};

// Throws InsufficientDataError when the log cannot give a reference (no GNSS fix inside the wheel
// span, or no way to find the heading).
enum class ReferenceCovariance { kDrop, kKeep };
ReferenceTrajectory compute_reference(const Log& log, const ReferenceOptions& options = {},
                                      ReferenceCovariance covariance = ReferenceCovariance::kDrop);

}  // namespace odocal
