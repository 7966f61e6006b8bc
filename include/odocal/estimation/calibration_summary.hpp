#pragma once
// What every calibration method reports (the common core of its summary, as Ceres'
// Solver::Summary): the estimate with its covariance, how the method ended, whether the result
// can be used, and the whole-log dead reckoning before and after. Each method's summary adds its
// own details (iterative_calibration.hpp, augmented_calibration.hpp, batch_calibration.hpp).

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "odocal/estimation/accelerometer_walk.hpp"
#include "odocal/estimation/log_preparation.hpp"
#include "odocal/estimation/model_adequacy.hpp"
#include "odocal/estimation/motion_coverage.hpp"
#include "odocal/model/odometry_model.hpp"
#include "odocal/model/tyre_model.hpp"
#include "odocal/options/enum_names.hpp"

namespace odocal {

enum class CalibrationMethod { kIterative, kFixedP, kAugmented, kBatch };
template <>
struct EnumNames<CalibrationMethod> {
  static constexpr std::array<EnumName<CalibrationMethod>, 4> kTable{
      {{CalibrationMethod::kIterative, "iterative"},
       {CalibrationMethod::kFixedP, "fixed-p"},
       {CalibrationMethod::kAugmented, "augmented"},
       {CalibrationMethod::kBatch, "batch"}}};
};
inline const char* method_name(CalibrationMethod method) { return enum_name(method); }

// How a calibration ended. Only kConverged is a usable result; for the others the summary's
// message says why, in words a user can act on.
enum class Termination {
  kConverged,        // the method reached its answer
  kNoConvergence,    // an iteration limit ended it while the estimate was still improving
  kNotIdentifiable,  // this log cannot determine the circumferences (to the required sigma)
  kImplausible,      // the numbers make no physical sense (not finite, ...)
  kFailure,          // the solver failed numerically
};
template <>
struct EnumNames<Termination> {
  static constexpr std::array<EnumName<Termination>, 5> kTable{
      {{Termination::kConverged, "converged"},
       {Termination::kNoConvergence, "no_convergence"},
       {Termination::kNotIdentifiable, "not_identifiable"},
       {Termination::kImplausible, "implausible"},
       {Termination::kFailure, "failure"}}};
};

// Whole-log dead reckoning against the reference.
struct DeadReckoningSummary {
  double mean_position_m{};
  double max_position_m{};
  double mean_heading_rad{};
  double max_heading_rad{};
};

struct CalibrationSummary {
  CalibrationMethod method{};
  Termination termination = Termination::kConverged;
  std::string message;  // why it stopped, or why the result is not usable
  std::string note;     // a caution that goes with a usable result; empty when there is none
  OdometryParams nominal;
  OdometryParams estimate;  // the nominal parameters where no estimate was reached
  // The condition-dependent part of the estimate (batch with tyre_model); plain otherwise.
  TyreModel tyre_model;
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();  // of [c_RL, c_RR], m^2
  double condition_number{};                             // of the circumference problem
  // false: c_RL / c_RR kept at the nominal ratio, only their common scale estimated.
  bool difference_identifiable = true;
  std::string identifiability;  // in words, for the user
  DeadReckoningSummary before;  // nominal parameters
  DeadReckoningSummary after;   // the estimate
  // What the accelerometer's noise alone makes of `after`'s heading through the tyre model
  // (accelerometer_walk.hpp); zero for the plain model or without an accelerometer.
  AccelerometerWalk accelerometer_walk;
  double distance_m{};         // wheel odometry distance while moving (= coverage.distance_m)
  MotionCoverage coverage;     // over the reference's span
  LogPreparation preparation;  // standstill, wheel rate bias, first motion, wheel gaps
  std::size_t reference_samples{};
  std::string reference_heading_source;
  // Whether the model explains the log (model_adequacy.hpp): the batch judges its own fit; for
  // the other methods the plain batch fit judges the two-wheel model (batch_fit.hpp). Empty
  // verdict: not judged (not usable, or judge_model_adequacy off).
  ModelAdequacy model_adequacy;
  // misfit_sigma_scale(model_adequacy) where the covariance was widened by it (above 1: the
  // residuals are wider than their noise); 1 otherwise.
  double misfit_sigma_scale = 1.0;
  // Where the plain model holds the track width: what track_width_uncertainty, the share of it
  // that the track the wheels roll on may lie from vehicle.yaml's, moves the circumferences by
  // (zero where the track is estimated or a tyre model is fitted; it is in sigma and covariance
  // too). The batch's own fit gives it; for the other methods the judge's plain fit of the log
  // (they hold the track too), where it judges.
  std::array<double, 2> track_sigma_m{};
  double track_width_uncertainty{};
  // The batch's plain fit only: the track was fitted under a prior of track_width_uncertainty
  // about vehicle.yaml's, not held (the tyre models judged the fit and its model explains the
  // log: docs/batch-calibration.md, "The track under its prior"). track_sigma_m is then the
  // track's part of the posterior sigma, the variance that the circumference shares with it.
  bool track_under_prior{};
  // The other methods only, which hold vehicle.yaml's track: where the judge's plain fit put the
  // track under its prior (as the batch's own would), the track it found and its sigma (NaN
  // otherwise). track_sigma_m is then the held track's share at that distance from it
  // (batch_fit.hpp, JudgedTrack).
  double judged_track_m = std::numeric_limits<double>::quiet_NaN();
  double judged_track_sigma_m = std::numeric_limits<double>::quiet_NaN();
  // Whether that share is worth naming in a report: a tenth of either circumference's sigma
  // (comma2k19, whose fixes and Doppler pin the scale: 0.0006 mm of 4.9 mm is not). The JSON
  // carries it, so that every report names it by this one rule.
  bool track_share_worth_naming() const;

  bool usable() const { return termination == Termination::kConverged; }
  double sigma_rl_m() const;  // 1-sigma from the covariance
  double sigma_rr_m() const;
  // One line: method, estimates with 1-sigma, termination.
  std::string brief_report() const;
};

}  // namespace odocal
