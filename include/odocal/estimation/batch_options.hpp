#pragma once
// Options of the batch maximum-likelihood calibration (`--method batch`, docs/calibration.md):
// keyframe poses and the parameters fitted to all wheel, GNSS, heading and gyro data at once.
// Sensor noise comes from CalibrationOptions::reference (gnss_sigma_m when gnss.csv has no
// sigma_m, heading_sigma_rad, yaw_rate_sigma_radps).

#include <array>
#include <string>

#include "odocal/model/tyre_model.hpp"
#include "odocal/options/option_fields.hpp"

namespace odocal {

enum class RobustLoss { kNone, kHuber, kCauchy };
template <>
struct EnumNames<RobustLoss> {
  static constexpr std::array<EnumName<RobustLoss>, 3> kTable{{{RobustLoss::kNone, "none"},
                                                               {RobustLoss::kHuber, "huber"},
                                                               {RobustLoss::kCauchy, "cauchy"}}};
};

// Which rolling circumference the batch fits (odocal/model/tyre_model.hpp): the plain model of
// eqs. 1-2, one that follows the driving state through regression terms (extended) or through
// the wheel's load and slip from the vehicle's body and the accelerometer (physical), or whichever
// the log supports by the Bayesian information criterion.
enum class TyreModelChoice { kNone, kExtended, kPhysical, kAuto };
template <>
struct EnumNames<TyreModelChoice> {
  static constexpr std::array<EnumName<TyreModelChoice>, 4> kTable{
      {{TyreModelChoice::kNone, "none"},
       {TyreModelChoice::kExtended, "extended"},
       {TyreModelChoice::kPhysical, "physical"},
       {TyreModelChoice::kAuto, "auto"}}};
};

struct BatchOptions {
  double keyframe_interval_s = 1.0;
  // Wheel noise: slip as a random walk in arc length; the encoder quantisation is derived from
  // vehicle.yaml's ticks_per_rev (sigma of a rounded count, 1/sqrt(12) tick).
  double slip_sigma_m_per_sqrt_m = 1e-3;
  double lateral_sigma_m_per_sqrt_m = 1e-3;  // side slip and model error across the course
  // Encoder quantisation per count in revolutions; negative: 1/sqrt(12) tick from ticks_per_rev
  // (0 for wheel angles or speeds); 0: counts taken as exact.
  double quantisation_sigma_rev = -1.0;
  // The rear wheels' tick difference fitted with a local quadratic over +-this before the fit,
  // their sum as counted (tick_dequantisation.hpp, heading_dequantised_ticks): the fixes between
  // keyframes meet a heading without the encoders' cut, which otherwise shortens the antenna's
  // fitted x by a few per cent (docs/batch-calibration.md, "The encoders' cut in the heading").
  // 0: as counted.
  double heading_tick_smoothing_s = 0.25;
  // Time-correlated GNSS error, a first-order Gauss-Markov process per axis (0: white only).
  // gnss.csv's sigma_m is then taken as the total and the white part is what remains.
  double gnss_gauss_markov_sigma_m = 0.0;
  double gnss_gauss_markov_tau_s = 60.0;
  RobustLoss gnss_loss = RobustLoss::kCauchy;
  double gnss_loss_scale = 3.0;  // in standard deviations of the fix
  // After the first solve, estimate the GNSS error from the residuals (white and Gauss-Markov)
  // and solve again with it when it differs from the configured noise (a white level off by
  // more than 25 %, or a correlated part above the stated one, which the adapted model keeps as
  // its least): the sigma then covers the error when the configured noise is wrong.
  bool adapt_gnss_noise = true;
  // Split-sample check (0: off): the log is calibrated again in this many consecutive parts of
  // equal duration, each with the whole log's tyre model, and the parts' circumferences are
  // compared with the whole log's by the Birge ratio R (BatchSummary::consistency). Where R is
  // above the chi-square bound (95 %), an error common to stretches of the log, which the
  // residuals hide (a GNSS error that wanders over tens of seconds), moves the estimate further
  // than its sigma says, and the circumferences' sigma is widened by R
  // (docs/batch-calibration.md, "A check that sees it"). It costs about one more fit of the log.
  int consistency_parts = 0;
  // gnss.csv's speed_mps column (Doppler speed over ground) against the wheels' distance over each
  // keyframe interval, with this white noise per fix; errors of fixes closer than
  // gnss_speed_correlation_s are taken as one (a receiver filters its velocity). 0: not used.
  // Negative (the default): kDefaultDopplerSigmaMps where the log has the column, widened by the
  // residuals where the receiver is noisier; it sharpens the physical tyre terms and is what
  // brings a realistic log's circumference at rest under the 1 mm threshold (docs/tyre-model.md,
  // "The Doppler speed"). Not by default under tyre_model: extended chosen by hand: the
  // regression terms' circumference at rest, an extrapolation along their fitted shape of the
  // slip, comes out confidently wrong with it on hard driving (auto carries that gap in its sigma).
  static constexpr double kDefaultDopplerSigmaMps = 0.05;
  double gnss_speed_sigma_mps = -1.0;
  double gnss_speed_correlation_s = 0.1;
  bool use_heading = true;  // heading.csv residuals
  bool use_gyro = true;     // imu.csv yaw-rate residuals
  // Extra unknowns on request (else held at: nominal track width, zero bias/lever arm/latency).
  bool estimate_track_width = false;
  bool estimate_gyro_bias = false;
  bool estimate_heading_bias = false;
  bool estimate_lever_arm = false;
  bool estimate_latency = false;
  // How far the track that the rear wheels roll on may lie from vehicle.yaml's track_width_m, as
  // a share of it, where the plain model holds the track: its spread goes into the
  // circumferences' sigma (0: exact; the tyre models carry the load that moves it). A turn's
  // wheel-speed difference over its yaw rate is the track over the circumference, so where GNSS
  // does not pin the distance (tight turns, a correlated GNSS error), the turns set the
  // circumferences' scale through the track, and load transfer moves the track the wheels roll on:
  // the realistic parking drive, plain model, -6 to -10 mm at a sigma of 1.3 to 1.9 mm; 1 % of the
  // track moves its circumferences by 9 to 17 mm (3 ideal laps of Hockenheim: 0.02 mm).
  // docs/batch-calibration.md, "The track the wheels roll on".
  double track_width_uncertainty = 0.01;
  // The GNSS antenna's position from the rear axle's centre (x forward, y left, m): held there,
  // or where estimate_lever_arm starts. An antenna off the centreline that the fit takes to be on
  // it runs y times the net turn shorter or longer than the wheels: 0.3 m on the 2-hour urban
  // drive of left-hand loops moved the circumferences by -4 mm (docs/batch-calibration.md, "The
  // mounting the log shows").
  double lever_arm_x_m = 0.0;
  double lever_arm_y_m = 0.0;
  // The GNSS fixes' latency behind the wheels (s; a fix stamped t reports the position at t minus
  // it): held there, or where estimate_latency starts. A receiver's known latency is stated here.
  double latency_s = 0.0;
  // Where the lever arm or heading.csv's bias is not estimated and the fit's residuals show it
  // (the GNSS fixes' mean error in the vehicle's frame, heading.csv's mean error against the
  // fitted heading, each beyond kMountingSigmas of its standard error and a size that matters),
  // the log is calibrated again with it estimated, and that fit stands where what it finds lies
  // beyond kMountingSigmas of its sigma. Only with judge_model_adequacy, as detect_latency.
  bool detect_mounting = true;
  static constexpr double kMountingSigmas = 5.0;
  // Where the latency is not estimated and a tyre model's fit leaves its along-track or Doppler
  // residual following the longitudinal acceleration (a lag tau between the GNSS and the wheels
  // leaves -tau a_x there, and the tyre terms have taken the slip), the log is calibrated again
  // with the latency estimated, and that fit stands where the latency it finds lies beyond
  // kLatencySigmas of its sigma (docs/batch-calibration.md, "A latency the log shows"). Only
  // with judge_model_adequacy: it judges the fit.
  bool detect_latency = true;
  static constexpr double kLatencySigmas = 5.0;
  // Gentle segments: only keyframe intervals whose every wheel sample stays below these limits
  // feed the odometry residuals (0: no limit); for logs whose tyre coefficients cannot be
  // identified (docs/tyre-model.md). GNSS and the gyro still place the poses everywhere.
  double gentle_max_speed_mps = 0.0;
  double gentle_max_longitudinal_mps2 = 0.0;
  double gentle_max_lateral_mps2 = 0.0;
  // auto by default: a log the plain model explains calibrates as under none, and one that it
  // does not (a driven rear wheel's slip, load transfer) gets the tyre model or, where the log
  // cannot pin the circumference at rest, a refusal instead of a confident wrong answer
  // (docs/tyre-model.md, "auto as the default").
  TyreModelChoice tyre_model = TyreModelChoice::kAuto;
  // Beside a tyre model, the steady straight speed whose effective circumference is reported
  // (BatchSummary::reference_circumference) and exported to ROS 2: gentle driving's.
  double reference_speed_mps = kDefaultReferenceSpeedMps;
  int max_solver_iterations = 100;
  // The odometry is pre-integrated at the current parameters and used to first order; when the
  // solution moves them by more than this fraction, it is integrated again and re-solved.
  double relinearise_relative_change = 1e-4;
  int max_relinearisations = 3;
  // Threads the batch's passes over the wheel samples and fixes run on: pre-integrating, folding,
  // measuring the driving states again, whitening the residuals (0: one per core). The result is
  // the same on any number.
  int threads = 0;
  // Observability: a parameter whose 1-sigma exceeds its threshold counts as not identified.
  double max_sigma_circumference_m = 1e-3;
  double max_sigma_track_width_m = 0.01;
  double max_sigma_gyro_bias_radps = 1e-3;
  double max_sigma_heading_bias_rad = 0.01;
  double max_sigma_lever_arm_m = 0.2;
  double max_sigma_latency_s = 0.02;
  // A tyre coefficient counts as not identified when its 1-sigma moves the circumference by
  // more than this fraction at the log's RMS value of its regressor (never: infinite sigma).
  double max_sigma_tyre_effect = 5e-4;

  static OptionTable<BatchOptions> fields();
  std::string validate() const;  // empty when valid
  // gnss_speed_sigma_mps for a log with (or without) gnss.csv's speed_mps column: the default
  // resolved, 0 where the column is missing.
  double doppler_sigma_mps(bool log_has_speed) const;
};

}  // namespace odocal
