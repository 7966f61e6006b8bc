#pragma once
// The batch maximum-likelihood calibration (docs/batch-calibration.md): keyframe poses and the
// parameters fitted by Ceres to all wheel, GNSS, heading and gyro data at once, with the
// covariance of every parameter and an observability verdict in words.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/estimation/batch_options.hpp"
#include "odocal/estimation/calibration_options.hpp"
#include "odocal/estimation/calibration_summary.hpp"
#include "odocal/estimation/model_adequacy.hpp"
#include "odocal/estimation/odometry_scales.hpp"
#include "odocal/model/tyre_model.hpp"

namespace odocal {

// One unknown of the batch calibration besides the poses.
struct EstimatedParameter {
  std::string name;  // e.g. "circumference_rl_m", "gyro_bias_radps"
  double value{};
  double sigma{};         // 1-sigma from the covariance; infinity when it could not be computed
  bool estimated{};       // false: held at its configured value (not asked for)
  bool identified{true};  // false: this log cannot pin it down (see the verdict)
  std::string verdict;    // in words a user can act on, when not identified
};

// The GNSS noise the fit saw in its residuals, against the configured one.
struct GnssNoiseReport {
  double configured_sigma_m{};  // RMS white sigma the first solve used per axis
  double residual_sigma_m{};    // RMS of its residuals per axis (outliers left out)
  double white_sigma_m{};
  double gauss_markov_sigma_m{};  // 0: no correlated error found
  double gauss_markov_tau_s{};
  bool adapted{};  // solved again with the estimated noise
  // The Gauss-Markov error the final solve assumed: the one in the residuals with its
  // correlation time raised to at least a tenth of the log (at the same random-walk intensity
  // sigma^2 / tau), because a fit hides the slow part of such an error in the trajectory.
  double model_gauss_markov_sigma_m{};
  double model_gauss_markov_tau_s{};
  // The circumferences' sigma after the adaptation over before (1 when not adapted).
  double sigma_inflation = 1.0;
  // The adapted estimate left the plausible band while the first did not: the first estimate
  // stands, its covariance scaled by covariance_scale (sigma_inflation^2, measured at the first
  // estimate under the adapted noise; infinite where it could not be measured).
  bool reverted{};
  double covariance_scale = 1.0;
};

// tyre_model auto: a tyre model fitted beside the plain one.
struct TyreCandidate {
  std::string model;                                     // "physical" or "extended"
  double bic = std::numeric_limits<double>::infinity();  // lower is better
  int solves{};
  // false: refused: coefficients that move a circumference by percents at the log's typical
  // state, or circumferences out of their plausible band (the model explains something else).
  bool tyre = true;
  // false: refused: the plain model with the track width freed fits the log as well (a track
  // that vehicle.yaml gets wrong, which the load terms mimic). Only where the track is held.
  bool beyond_track = true;
  // Fitted with the track width free: where auto freed the track for its plain comparison, each
  // candidate's criterion is taken both ways, and it is fitted the way whose criterion (`bic`)
  // is lower. Both criteria are kept (NaN where only the held one was taken).
  bool track_free = false;
  double held_track_bic = std::numeric_limits<double>::quiet_NaN();
  double free_track_bic = std::numeric_limits<double>::quiet_NaN();
  // Where the track freed won and was fitted held too: each fit's whole-log dead reckoning
  // (mean position error + 10 m/rad of mean heading error, m). The freed track stands only where
  // it dead-reckons the log better than vehicle.yaml's (NaN where not compared).
  double held_track_score_m = std::numeric_limits<double>::quiet_NaN();
  double free_track_score_m = std::numeric_limits<double>::quiet_NaN();
  // false: refused: its circumferences at rest were not identified (sigma above
  // max_sigma_circumference_m) and agree with the identified plain fit's: the plain fit's sigma
  // widened by the gap between them is still within max_sigma_circumference_m. (Where they do
  // not, the candidate stands: the plain fit's sigma leaves out what moves it.)
  bool needed = true;
  // false: refused: it won the BIC, but its whole-log dead reckoning is worse than the nominal
  // parameters' (implausible) where the best fit before it was not.
  bool dead_reckons = true;
  // Its circumferences at rest (NaN where its fit was not usable).
  std::array<double, 2> circumference{std::numeric_limits<double>::quiet_NaN(),
                                      std::numeric_limits<double>::quiet_NaN()};
  // true: the log identified none of its coefficients (every one held, at a car's value or at
  // zero). Such a fit cannot stand, since nothing of it is the log's; where it fits the log
  // decisively better all the same, the plain circumferences carry their gap to it.
  bool every_coefficient_held = false;
  // true: not chosen, it judges the plain fit by its fit under the GNSS noise that the residuals
  // show, since its own, under the configured noise, wandered (facts_to_judge_by): it cannot be
  // chosen until that noise is stated.
  bool judged_under_noise_shown = false;
  // Whether it may stand, or judge a plain fit, by fitting the log better.
  bool can_stand() const { return tyre && !every_coefficient_held; }
  // Whether its fit was usable: it has circumferences at rest to carry a gap to.
  bool fitted() const { return std::isfinite(circumference[0]) && std::isfinite(circumference[1]); }
};

// tyre_model auto: the information criteria of every model fitted and which one stands. Under
// tyre_model none chosen by hand (and judge_model_adequacy), the tyre models' fits as the plain
// fit's judges, the track width free in each: `chosen` stays "none", and where a candidate is
// `needed` (a tyre that wins the criterion) the plain circumferences carry their gap to its in
// their sigma.
struct TyreModelSelection {
  bool compared = false;
  bool judges_plain = false;
  double plain_bic{};
  // The plain model's with the track width freed, where auto fitted it (the track held and the
  // plain fit's heading residual following the curvature; NaN otherwise).
  double free_track_bic = std::numeric_limits<double>::quiet_NaN();
  // The better of the plain fits, which the tyre models are compared with: the geometry explains
  // what the track freed does.
  double compared_plain_bic() const {
    return std::isfinite(free_track_bic) ? std::min(plain_bic, free_track_bic) : plain_bic;
  }
  // The plain model stands with the track width free: it fitted the log better so than with the
  // track held, and no tyre model stood.
  bool plain_track_free = false;
  std::vector<TyreCandidate> candidates;  // in the order fitted
  std::string chosen = "none";
  // Where the plain model stands judged: the candidate whose circumferences at rest the plain
  // ones carry their gap to in their sigma (empty: none). Under tyre_model none, a tyre that fits
  // the log better; under either, where no candidate does, one that fits it decisively better
  // without being a tyre (the plain model does not explain the log, and no model here says
  // surely where the circumferences at rest lie).
  std::string plain_gap_to;
  // The share of that gap the plain circumferences carry: 1 where the judge fits the log better
  // (or cannot stand), the criteria's weighed share (tie_gap_share) where it fits it about as
  // well; 0 where they carry none.
  double plain_gap_share = 0.0;
  // Where a tyre model stands: the one whose circumferences at rest its own carry their gap to in
  // their sigma (empty: none). The regression terms carry their gap to the physical ones where
  // those were fitted; the physical terms theirs to the regression terms, which need no body,
  // where the two disagree beyond kWitnessSigmas of their combined sigma (a body that
  // vehicle.yaml gets wrong: batch_fit.hpp, witness_physical_fit), how far being
  // chosen_gap_sigmas.
  std::string chosen_gap_to;
  double chosen_gap_sigmas = std::numeric_limits<double>::quiet_NaN();
  // The physical terms stand carrying their gap to the regression terms: the body is in doubt.
  bool body_in_doubt() const { return chosen_gap_to == tyre_model_option(TyreTerms::kRegression); }
  int other_solves{};  // the solves of the fits not chosen (BatchSummary::solves: the chosen's)
};

// Beside a tyre model: each rear wheel's effective circumference rolling straight at a steady
// reference speed, slip and load included: the one constant that stands for the tyre model in
// gentle driving (garages, urban canyons: where dead reckoning is needed), and what a consumer of
// constant radii (the ROS 2 export) is given. Its sigma is the circumference's at rest, nearly:
// the body numbers that the log cannot separate from c_i move both alike.
struct ReferenceCircumference {
  double speed_mps{};
  double circumference_rl_m{}, circumference_rr_m{};
  double sigma_rl_m{}, sigma_rr_m{};
  bool identified{};  // both sigmas within max_sigma_circumference_m (reported, not judged)
};

// BatchOptions::consistency_parts: the log calibrated again in consecutive parts, each part's
// circumferences against the whole log's.
struct PartsConsistency {
  struct Part {
    double from_s{}, to_s{};  // the log's clock
    // false: the part could not be fitted (too little in it, or its solve failed): left out.
    bool fitted{};
    std::array<double, 2> circumference_m{}, sigma_m{};
  };
  std::vector<Part> parts;
  std::size_t fitted_parts{};
  // Per rear wheel: sqrt(sum over the fitted parts of ((c_k - c) / sigma_k)^2 / (n - 1)), c the
  // whole log's estimate; about 1 where the sigmas are right. NaN with fewer than 2 parts.
  std::array<double, 2> birge_ratio{};
  double bound{};  // the chi-square 95 % quantile for n - 1 degrees of freedom, as a ratio
  bool consistent = true;
  // The factor the circumferences' sigma was widened by (1: not widened).
  std::array<double, 2> sigma_scale{1.0, 1.0};
  std::string verdict;  // in words
};

// What a fit's residuals say of the sensors' mounting (BatchOptions::detect_mounting): the GNSS
// fixes' mean error turned into the vehicle's frame (where the antenna sits off the lever arm the
// fit holds) and heading.csv's mean error against the fitted heading (a mount's yaw offset), each
// with the standard error of that mean from the keyframe intervals' means, their lag-1
// correlation taken in (a GNSS error that wanders is no offset).
struct MountingResiduals {
  std::array<double, 2> gnss_mean_m{}, gnss_standard_error_m{};  // [ahead, left]
  double heading_mean_rad{}, heading_standard_error_rad{};
  // Where the Doppler speed is in the fit: the antenna's left offset that its residual shows. An
  // antenna y left of the centre runs -y times the interval's turn beside the wheels: minus the
  // slope of the Doppler residual over the intervals' turns, with its standard error.
  double doppler_left_m{}, doppler_left_standard_error_m{};
  bool gnss{}, heading{}, doppler{};  // measured: enough keyframe intervals with each
};

struct BatchSummary : CalibrationSummary {
  std::vector<EstimatedParameter> parameters;  // every unknown besides the poses
  std::string solver_report;                   // Ceres' brief report of the last solve
  std::size_t keyframes{};
  std::size_t gnss_fixes{};  // GNSS residuals in the problem
  // Keyframe intervals whose Doppler speed (gnss.csv's speed_mps) is in the problem.
  std::size_t doppler_intervals{};
  // Their noise against the configured gnss_speed_sigma_mps: above 1 where the residuals showed
  // more scatter and the fit was solved again with it.
  double doppler_sigma_scale = 1.0;
  // Of the fit returned: the first, coarse one, the re-linearisations, the adapted one.
  int solves{};
  GnssNoiseReport gnss_noise;
  // Of [c_RL, c_RR, t_R] (m^2), inflated as the GNSS noise report says; infinite when Ceres
  // could not compute it.
  Eigen::Matrix3d params_covariance = Eigen::Matrix3d::Zero();
  // The speed and yaw-rate scales of the calibrated model against the nominal one; set when the
  // track was estimated (twist odometry, robots).
  std::optional<OdometryScales> odometry_scales;
  TyreModelSelection tyre_selection;
  // The physical terms' share of the circumferences' sigma: what the body's uncertainty moves
  // them by (zero for any other model; it is in sigma and covariance too).
  std::array<double, 2> body_sigma_m{};
  // Each body number's part of it: what its uncertainty alone moves each circumference by (the
  // parts add in squares to body_sigma_m), so that a user knows which number to measure.
  struct BodySigmaPart {
    std::string key;  // vehicle.yaml body's
    std::array<double, 2> sigma_m{};
  };
  std::vector<BodySigmaPart> body_sigma_parts;
  // The physical coefficients held (the log cannot identify them), likewise: what each one's
  // spread about where it is held (a car's value, narrowed by what the log said of it) moves the
  // circumferences by (zero for any other model and where none is held; it is in sigma and
  // covariance too).
  std::array<double, 2> held_sigma_m{};
  struct HeldSigmaPart {
    std::string key;  // the parameter's name, tyre_...
    std::array<double, 2> sigma_m{};
    double coefficient_sigma{};  // the coefficient's spread about its held value that was taken
  };
  std::vector<HeldSigmaPart> held_sigma_parts;
  // The physical terms take imu.csv's forward reading for drive force: what is left of its
  // offset after preparing (LogPreparation::accelerometer_offset; where fewer than 3 stops
  // measured it, 0.1 m/s^2 or what driving straight reads, if more) moves the circumferences by
  // this much (zero for any other model and without imu.csv; it is in sigma and covariance too).
  std::array<double, 2> forward_offset_sigma_m{};
  double forward_offset_sigma_mps2{};
  // The regression terms' share of the circumferences' sigma under tyre_model auto: their gap to
  // the physical terms' fit of the same log (zero otherwise; it is in sigma and covariance too).
  std::array<double, 2> model_spread_m{};
  std::optional<ReferenceCircumference> reference_circumference;
  // Gentle segments (BatchOptions::gentle_max_*): keyframe intervals whose odometry is in the fit,
  // of all; equal without limits (gaps aside).
  bool gentle_limits{};
  std::size_t odometry_intervals_used{};
  std::size_t odometry_intervals{};
  // The split-sample check (BatchOptions::consistency_parts); none where it is off or the whole
  // log's result was not usable.
  std::optional<PartsConsistency> consistency;
  // BatchOptions::detect_latency: where the fit without the latency left its residual following
  // the longitudinal acceleration (or its Doppler or fixes' noise widened), the latency
  // estimated, and whether that fit stands.
  struct LatencyDetection {
    ResidualDependence signature;  // what the fit without the latency left
    // That fit's Doppler noise over the configured; where the residuals showed no dependence on
    // a_x (the regression terms took it), a scale beyond kLagDopplerScale was the sign looked at.
    double doppler_sigma_scale{1.0};
    bool by_doppler_noise{};
    // That fit's GNSS fixes' residual RMS over their configured noise; a scale beyond
    // kLagGnssScale was the sign looked at where neither of the above was.
    double gnss_sigma_scale{1.0};
    bool by_gnss_noise{};
    // The latency beyond kLatencySigmas of its sigma from the stated; looked for by a noise,
    // taken only where the fit with it brings that noise under kLagDopplerScale (the fixes':
    // kLagGnssExplained).
    bool significant{};
    double doppler_sigma_scale_with{1.0};
    double gnss_sigma_scale_with{1.0};
    double latency_s{}, sigma_s{};
    bool taken{};  // the latency beyond kLatencySigmas of its sigma: this summary is that fit
    std::array<double, 2> circumference_without_m{};  // the fit without the latency's
  };
  std::optional<LatencyDetection> latency_detection;
  MountingResiduals mounting_residuals;  // of the fit returned
  // BatchOptions::detect_mounting: where the fit without them showed the antenna's lever arm or
  // heading.csv's bias, the fit with them estimated, and whether it stands.
  struct MountingDetection {
    MountingResiduals signature;       // what the fit without them left
    bool lever_arm{}, heading_bias{};  // which were estimated
    std::array<double, 2> lever_arm_m{}, lever_arm_sigma_m{};
    double heading_bias_rad{}, heading_bias_sigma_rad{};
    bool fitted{};  // the fit with them estimated stood (converged, or only not identified)
    bool taken{};   // one of them beyond kMountingSigmas of its sigma: this summary is that fit
                    // (or, where a latency was found after, the one it was fitted from)
    std::array<double, 2> circumference_without_m{}, circumference_with_m{};
    // Taken, then found to be the lag's: with the latency estimated beside it, it was no longer
    // significant, and the log was calibrated again with the latency alone (taken: false).
    bool explained_by_latency{};
    // The lever arm not shown by the residuals' means but by the fixes' noise: the fit without it
    // left them kLagGnssExplained times their configured noise or more, and the one with it
    // brought them under (by_gnss_noise); or a significant latency's fit left them so, and the
    // lever arm estimated beside it brought them under (found_beside_latency; this summary is the
    // fit of both). The fixes' scale without the lever arm (with the latency alone) and with.
    bool by_gnss_noise{}, found_beside_latency{};
    double gnss_sigma_scale_without{1.0}, gnss_sigma_scale_with{1.0};
    // A heading bias the first fits' residuals did not show (their fixes far off the path, the
    // poses followed heading.csv) and the fit that a latency or a lever arm found after left did:
    // its heading mean and standard error there, and the circumferences without and with the bias
    // estimated beside them. heading_bias and its value are then that fit's; this summary is it.
    struct HeadingAfter {
      bool beside_latency{};  // a latency taken (or only a lever arm)
      double seen_rad{}, seen_standard_error_rad{};
      std::array<double, 2> circumference_without_m{}, circumference_with_m{};
    };
    std::optional<HeadingAfter> heading_after;
  };
  std::optional<MountingDetection> mounting_detection;

  std::string full_report() const;
};

// Throws for invalid options and for a log too short to try; every other outcome (not
// converged, not identified) is in the summary. Poses start from the layer-1 reference,
// parameters from the nominal vehicle. Never reads log.truth.
BatchSummary calibrate_batch(const Log& log, const BatchOptions& options = {},
                             const CalibrationOptions& common = {});

// Where the fit found the GNSS antenna (forward and left of the rear axle's centre, m): where it
// estimated the lever arm (estimate_lever_arm, or detect_mounting's fit taken) and the log
// identified both coordinates. Nothing where it was held (at vehicle.yaml's gnss_x_m, gnss_y_m or
// the configured place).
std::optional<Eigen::Vector2d> fitted_antenna_place(const BatchSummary& summary);

}  // namespace odocal
