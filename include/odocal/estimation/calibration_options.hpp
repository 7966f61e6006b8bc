#pragma once
// What every calibration method shares (docs/calibration.md): the layer-1 reference, how far the
// odometry filters trust it, how the whole-log dead reckoning that judges an estimate starts,
// and when a log is too short or too straight to identify the circumferences.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <string>

#include "odocal/estimation/motion_coverage.hpp"
#include "odocal/estimation/reference_filter.hpp"
#include "odocal/estimation/standstill.hpp"
#include "odocal/options/option_fields.hpp"

namespace odocal {

// Where the whole-log dead reckoning of each estimate starts (the paper is silent): the first
// reference pose; the rigid alignment (Umeyama) of the dead-reckoned path to the reference over
// the first dr_align_window_s; or over the whole log.
enum class DeadReckoningStart { kFirstReference, kAlignedWindow, kAlignedWhole };
template <>
struct EnumNames<DeadReckoningStart> {
  static constexpr std::array<EnumName<DeadReckoningStart>, 3> kTable{
      {{DeadReckoningStart::kFirstReference, "first-reference"},
       {DeadReckoningStart::kAlignedWindow, "aligned-window"},
       {DeadReckoningStart::kAlignedWhole, "aligned-whole"}}};
};

struct CalibrationOptions {
  ReferenceOptions reference;
  // M of the paper (eq. 13a): the covariance of the reference pose [x m^2, y m^2, yaw rad^2] in
  // the odometry filters (layer 2 and the augmented KF).
  Eigen::Vector3d measurement_diagonal{1.0, 1.0, 0.01};
  DeadReckoningStart dr_start = DeadReckoningStart::kAlignedWindow;
  double dr_align_window_s = 60.0;
  // Plausibility: an estimate further than this fraction from the nominal circumference is not a
  // result (units, ticks_per_rev, a time scale); nor is one that dead-reckons the log worse than
  // the nominal parameters by more than max_dead_reckoning_increase (relative, above 0.5 m).
  double max_relative_change = 0.05;
  double max_dead_reckoning_increase = 0.05;
  // A wheel-stream interval longer than this is a gap: the odometry chain breaks there
  // (wheel_gaps.hpp). 0: five times the median wheel sample period.
  double max_wheel_gap_s = 0.0;
  // Too little data: refused before any estimate (InsufficientDataError).
  double min_distance_m = 100.0;
  std::size_t min_reference_samples = 100;
  // Below this much turning while moving (left and right together, measured on the gyro or the
  // wheels: motion_coverage.hpp), a left/right circumference difference cannot be told from a
  // gyro or heading bias: only a common scale of the nominal circumferences is estimated, and the
  // summary says so.
  double min_turning_for_difference_rad = 0.785;  // 45 deg
  MotionCoverageOptions coverage;
  // Standing still (standstill.hpp): the zero-rate bias of angular-rate wheel sensors (radps, mps)
  // is estimated there and removed, and the log is used from its first motion on. So is the
  // accelerometer's forward offset (accelerometer_offset.hpp).
  StandstillOptions standstill;
  bool remove_wheel_rate_bias = true;
  bool remove_accelerometer_offset = true;
  bool start_at_first_motion = true;
  // Hills (road_grade.hpp): with gnss.csv's alt column, the wheel increments are projected to
  // the horizontal with the grade fitted over grade_window_m of driving.
  bool use_gnss_altitude = true;
  double grade_window_m = 100.0;
  // A long log is prepared a block of this length at a time (prepared_blocks.hpp).
  double prepare_block_s = 600.0;
  // After an iterative, fixed-P or augmented calibration: whether the two-wheel model explains
  // the log, judged on a plain batch fit (one batch solve more; the batch method always judges
  // its own fit). The batch's tyre models chosen by hand are judged by the other family.
  bool judge_model_adequacy = true;

  static OptionTable<CalibrationOptions> fields();  // without `reference` (its own table)
  std::string validate() const;                     // empty when valid; includes `reference`
};

}  // namespace odocal
