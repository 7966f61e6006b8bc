#include "odocal/estimation/calibration_options.hpp"

#include <array>

namespace odocal {

OptionTable<ReferenceOptions> ReferenceOptions::fields() {
  using O = ReferenceOptions;
  static const std::array<OptionField<O>, 23> kFields{{
      {"mode", "", 0, 0, "filter (the paper's causal filter) or smoother (off-line RTS pass)",
       enum_member<&O::mode>()},
      {"gnss_sigma_m", "m", 1e-6, 1e4, "GNSS horizontal 1-sigma when gnss.csv has no sigma_m",
       &O::gnss_sigma_m},
      {"heading_sigma_rad", "rad", 1e-6, 10.0, "heading.csv 1-sigma", &O::heading_sigma_rad},
      {"acc_sigma_mps2", "m/s^2", 1e-6, 100.0, "IMU acceleration noise per sample",
       &O::acc_sigma_mps2},
      {"yaw_rate_sigma_radps", "rad/s", 1e-6, 10.0, "IMU yaw-rate noise per sample",
       &O::yaw_rate_sigma_radps},
      {"acc_random_walk_mps2", "m/s^2/sqrt(s)", 0.0, 100.0,
       "extra acceleration random walk for what the IMU model misses", &O::acc_random_walk_mps2},
      {"yaw_random_walk_radps", "rad/s/sqrt(s)", 0.0, 10.0,
       "extra yaw-rate random walk for what the IMU model misses", &O::yaw_random_walk_radps},
      {"no_imu_acc_psd", "m^2/s^3", 1e-6, 1e4,
       "without imu.csv: white acceleration spectral density", &O::no_imu_acc_psd},
      {"no_imu_yaw_rate_psd", "rad^2/s", 1e-6, 100.0,
       "without imu.csv: white yaw-rate spectral density", &O::no_imu_yaw_rate_psd},
      {"lateral_velocity_sigma_mps", "m/s", 0.0, 100.0,
       "the rear axle's velocity across its heading beyond the side slip, 1-sigma per GNSS fix; "
       "0: off (the paper's layer 1)",
       &O::lateral_velocity_sigma_mps},
      {"lateral_velocity_min_speed_mps", "m/s", 0.0, 100.0,
       "no lateral-velocity update below this speed", &O::lateral_velocity_min_speed_mps},
      {"lateral_velocity_max_turn_radps", "rad/s", 0.0, 10.0,
       "no lateral-velocity update where the gyro turns faster (side slip, the antenna's place)",
       &O::lateral_velocity_max_turn_radps},
      {"lateral_velocity_max_lateral_mps2", "m/s^2", 0.0, 100.0,
       "no lateral-velocity update where speed times the gyro's turn exceeds this",
       &O::lateral_velocity_max_lateral_mps2},
      {"course_min_speed_mps", "m/s", 0.0, 100.0,
       "without heading.csv, where the lateral-velocity update does not apply: the GNSS course "
       "corrects yaw above this speed",
       &O::course_min_speed_mps},
      {"course_sigma_rad", "rad", 1e-6, 10.0, "1-sigma of the GNSS course as a heading",
       &O::course_sigma_rad},
      {"gnss_gate_chi2", "1", 0.0, 1e6, "> 0: reject GNSS fixes whose NIS (2 dof) exceeds this",
       &O::gnss_gate_chi2},
      {"acc_bias_sigma_mps2", "m/s^2", 0.0, 100.0, "initial 1-sigma of the accelerometer biases",
       &O::acc_bias_sigma_mps2},
      {"gyro_bias_sigma_radps", "rad/s", 0.0, 10.0, "initial 1-sigma of the gyro bias",
       &O::gyro_bias_sigma_radps},
      {"acc_bias_random_walk_mps2", "m/s^2/sqrt(s)", 0.0, 100.0, "accelerometer bias random walk",
       &O::acc_bias_random_walk_mps2},
      {"gyro_bias_random_walk_radps", "rad/s/sqrt(s)", 0.0, 10.0, "gyro bias random walk",
       &O::gyro_bias_random_walk_radps},
      {"use_gnss_speed", "", 0, 0, "gnss.csv speed_mps (Doppler) updates |v| when present",
       &O::use_gnss_speed},
      {"gnss_speed_sigma_mps", "m/s", 1e-6, 100.0, "1-sigma of the Doppler speed",
       &O::gnss_speed_sigma_mps},
      {"gnss_speed_min_mps", "m/s", 0.0, 100.0, "no speed update below this speed",
       &O::gnss_speed_min_mps},
  }};
  return kFields;
}

std::string ReferenceOptions::validate() const { return check_option_ranges(fields(), *this); }

OptionTable<CalibrationOptions> CalibrationOptions::fields() {
  using O = CalibrationOptions;
  static const std::array<OptionField<O>, 16> kFields{{
      {"measurement_diagonal", "[m^2, m^2, rad^2]", 1e-12, 1e12,
       "M (eq. 13a): covariance of the reference pose in the odometry filters",
       &O::measurement_diagonal},
      {"dr_start", "", 0, 0, "start of the whole-log dead reckoning that scores an estimate",
       enum_member<&O::dr_start>()},
      {"dr_align_window_s", "s", 1.0, 1e6, "aligned-window: length of the alignment window",
       &O::dr_align_window_s},
      {"max_relative_change", "1", 1e-4, 10.0,
       "an estimate further than this fraction from nominal is implausible (not a result)",
       &O::max_relative_change},
      {"max_dead_reckoning_increase", "1", 0.0, 100.0,
       "implausible when the estimate dead-reckons worse than nominal by more than this",
       &O::max_dead_reckoning_increase},
      {"max_wheel_gap_s", "s", 0.0, 1e4,
       "a longer wheel-stream interval breaks the odometry chain (0: 5 median sample periods)",
       &O::max_wheel_gap_s},
      {"remove_wheel_rate_bias", "", 0, 0,
       "estimate the zero-rate bias of angular-rate wheel sensors at standstill and remove it",
       &O::remove_wheel_rate_bias},
      {"remove_accelerometer_offset", "", 0, 0,
       "measure imu.csv's forward offset (a mount's pitch) at standstill, or over the drive where "
       "too few stops show it, and remove it from ax",
       &O::remove_accelerometer_offset},
      {"start_at_first_motion", "", 0, 0, "use the log from its first motion on",
       &O::start_at_first_motion},
      {"use_gnss_altitude", "", 0, 0,
       "with an alt column in gnss.csv, project the wheels to the horizontal (hills)",
       &O::use_gnss_altitude},
      {"grade_window_m", "m", 10.0, 1e5, "the road grade is fitted over this much driving",
       &O::grade_window_m},
      {"prepare_block_s", "s", 120.0, 1e7,
       "a long log is prepared (standstill, bias, grade, gaps) in blocks of this length",
       &O::prepare_block_s},
      {"judge_model_adequacy", "", 0, 0,
       "judge the two-wheel model: iterative, fixed-p, augmented on a plain batch fit, each and "
       "the batch under tyre_model none against the tyre models' fits, whose gap to the "
       "estimate enters its sigma where one fits the log better, the batch's physical "
       "terms against the regression terms, where they disagree, and its regression terms "
       "chosen by hand against the physical terms (a few solves more)",
       &O::judge_model_adequacy},
      {"min_distance_m", "m", 0.0, 1e9, "refuse logs with less wheel odometry than this",
       &O::min_distance_m},
      {"min_reference_samples", "1", 2.0, 1e9, "refuse logs with fewer reference samples",
       &O::min_reference_samples},
      {"min_turning_for_difference_rad", "rad", 0.0, 1e4,
       "below this much turning while moving only the common scale of c_RL and c_RR is estimated",
       &O::min_turning_for_difference_rad},
  }};
  return kFields;
}

std::string CalibrationOptions::validate() const {
  if (std::string problem = reference.validate(); !problem.empty()) return "reference." + problem;
  if (std::string problem = coverage.validate(); !problem.empty()) return "coverage." + problem;
  if (std::string problem = standstill.validate(); !problem.empty()) return "standstill." + problem;
  return check_option_ranges(fields(), *this);
}

}  // namespace odocal
