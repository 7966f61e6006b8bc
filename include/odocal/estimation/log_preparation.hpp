#pragma once
// What every command does to a log before the odometry is used: for a calibration, only the span
// that both wheels and GNSS cover is used (a wheel stream hours past the last fix, from a clock
// jump, would otherwise be odometry with no reference); the zero-rate bias of angular-rate wheel
// sensors and the accelerometer's forward offset (where it stands out of its noise), estimated
// at standstill, are removed; the log is used from its first motion on; on hills the wheels are
// projected to the horizontal; and the odometry chain breaks at wheel gaps. The record of it goes
// into reports.

#include <optional>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/estimation/accelerometer_offset.hpp"
#include "odocal/estimation/calibration_options.hpp"
#include "odocal/estimation/drive_forward_offset.hpp"
#include "odocal/estimation/road_grade.hpp"
#include "odocal/estimation/standstill.hpp"
#include "odocal/estimation/wheel_gaps.hpp"

namespace odocal {

struct LogPreparation {
  // Wheels beyond the GNSS span cut off: the kept span and what was cut, s.
  std::optional<std::pair<double, double>> common_span_s;
  double cut_without_gnss_s{};
  std::vector<Standstill> standstills;
  // Removed (angular-rate wheel sensors only): the mean over the blocks weighted by their
  // standing time, and each block's own (prepared_blocks.hpp: a long log is prepared in blocks).
  std::optional<WheelRateBias> wheel_rate_bias;
  struct BlockBias {
    double from_s{};
    WheelRateBias bias;
  };
  std::vector<BlockBias> wheel_rate_bias_per_block;
  // The accelerometer's forward offset (imu.csv only), from every stop's reading, removed where
  // it stands out of its sigma (AccelerometerOffset::removed): the whole log's estimate from
  // every block (below).
  std::vector<StopReading> forward_readings;
  std::optional<AccelerometerOffset> accelerometer_offset;
  // Where fewer than 3 stops measured it: the drive's own measure (drive_forward_offset.hpp),
  // removed where it stands out of its sigma, or where the drive cannot tell the slope from it,
  // the forward reading while driving straight less the wheels' acceleration
  // (driving_forward_offset; a calibration's, not removed).
  std::optional<DriveForwardOffset> drive_forward_offset;
  std::optional<double> driving_forward_offset_mps2;
  // What the last block removed from ax (0: nothing).
  double removed_forward_mps2{};
  // A single pass's blocks each remove the estimate of their time: the time-weighted RMS of what
  // they removed less what the last one did. prepare_log prepares such a log again with the last
  // block's removed from every block; only a streamed dead reckoning that was not given the
  // whole log's (LogDeadReckoningOptions::forward_offset_mps2) keeps it.
  double unevenly_removed_forward_mps2{};
  // Where a single pass's blocks removed different offsets: the last block's (the whole log's),
  // for a second pass to remove from every block.
  std::optional<double> forward_offset_for_every_block() const {
    if (!(unevenly_removed_forward_mps2 > 0.0)) return std::nullopt;
    return removed_forward_mps2;
  }
  std::optional<double> started_at_s;  // used from here on (first motion)
  std::vector<WheelGap> wheel_gaps;    // where the odometry chain breaks
  // Hills: the grade 95 % of the road stays within, and how much longer the 3-D path was
  // (projected to the horizontal).
  std::optional<double> typical_max_grade;
  double length_excess{};
  double grade_scale_variance{};  // relative; the summary's covariance includes it

  double standing_s() const;
  // One line for reports ("" when nothing was done): standstill, bias, start, gaps.
  std::string describe() const;
};

// The prepared log, or nothing when preparing changes nothing (then use `log` itself); `done`
// records what was found and done. Uses options' standstill, remove_wheel_rate_bias,
// remove_accelerometer_offset, start_at_first_motion, coverage.moving_speed_mps, max_wheel_gap_s,
// use_gnss_altitude, grade_window_m and prepare_block_s (prepared_blocks.hpp: one block after
// another). `need_gnss_span`: cut the wheels to the GNSS span (calibration and validation; dead
// reckoning drives on where GNSS is missing). Throws InsufficientDataError when wheels and GNSS
// share less than 2 s.
std::optional<Log> prepare_log(const Log& log, const CalibrationOptions& options,
                               LogPreparation& done, bool need_gnss_span = true);

}  // namespace odocal
