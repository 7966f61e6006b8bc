#pragma once
// What the doctor needs of a log besides its comparison grid: the streams' spans, repeated GNSS
// fixes, gaps, standstills and their biases; gathered with the grid a block at a time
// (prepared_blocks.hpp), so that the doctor holds its 10 Hz grid and one block of the log,
// never the whole of it. A log shorter than two blocks is one block: the whole log at once.

#include <optional>
#include <utility>
#include <vector>

#include "diagnosis_signals.hpp"
#include "odocal/data/log_source.hpp"
#include "odocal/estimation/drive_forward_offset.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/standstill.hpp"
#include "odocal/estimation/wheel_gaps.hpp"

namespace odocal::detail {

struct StreamSpan {
  double first_s{};
  double last_s{};
  std::size_t samples{};
};

struct DiagnosisFacts {
  VehicleConfig vehicle;
  WheelUnit wheel_unit{};
  bool gnss_geodetic{};  // given as lat/lon
  bool gnss_altitude{};
  StreamSpan wheels, gnss, imu, heading;  // samples 0: the log has no such stream
  std::size_t gnss_repeated{};            // rows that repeat the row before
  std::size_t gnss_first_repeated_row{};  // 0-based
  std::vector<WheelGap> wheel_gaps;       // beyond five median sample periods of their block
  // The longest GNSS interval beyond max(2 s, 10 of its block's median), and that median.
  std::optional<std::pair<double, double>> gnss_gap;
  bool standing{};  // the wheels, GNSS and gyro agree on a standstill somewhere
  // The gyro's and the accelerometer's forward readings over the standstills.
  WindowSum gyro_standing, ax_standing;
  // Angular-rate wheel sensors: the median rate over each block's standstills, averaged over the
  // blocks by their standing time.
  std::optional<WheelRateBias> wheel_rate_bias;
  // The accelerometer's forward offset over the drive, where the altitude's grade or a closed
  // loop tells the slope from it (drive_forward_offset.hpp).
  std::optional<DriveForwardOffset> drive_forward_offset;
};

// Reads `source` from its first wheel sample to its end; the grid goes into `signals`.
DiagnosisFacts diagnosis_facts(LogBlockSource& source, DiagnosisSignals& signals,
                               double step_s = 0.1);

}  // namespace odocal::detail
