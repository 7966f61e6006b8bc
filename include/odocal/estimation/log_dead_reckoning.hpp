#pragma once
// A whole log dead-reckoned as `odocal deadreckon` does it: prepared (log_preparation.hpp),
// started from truth or GNSS, restarted from the reference where the chain breaks, and compared
// with truth (else GNSS and heading) — one prepared block at a time (prepared_blocks.hpp), so
// that a log streamed from its files (odocal/io/log_block_reader.hpp) is never held whole.

#include <functional>
#include <optional>
#include <string>

#include "odocal/data/log_source.hpp"
#include "odocal/estimation/log_preparation.hpp"
#include "odocal/estimation/tick_dequantisation.hpp"
#include "odocal/estimation/trajectory_errors.hpp"
#include "odocal/model/tyre_model.hpp"

namespace odocal {

enum class LogStart { kAuto, kTruth, kGnss };  // auto: truth when the log has it

struct LogDeadReckoningOptions {
  std::optional<double> circumference_rl_m, circumference_rr_m, track_width_m;  // else nominal
  bool plain = false;  // ignore vehicle.yaml's tyre_model
  LogStart start = LogStart::kAuto;
  // Tick counts averaged over +-this before dead reckoning (tick_dequantisation.hpp); 0: as
  // counted.
  double tick_smoothing_s = kDefaultTickSmoothingS;
  CalibrationOptions preparation;  // prepared as every command prepares a log (the defaults)
  // The accelerometer's forward offset that a first pass over the whole log measured
  // (whole_log_forward_offset), removed from every block: else a long log's blocks remove the
  // running estimate of their time (the tyre model takes ax).
  std::optional<double> forward_offset_mps2;
};

struct LogDeadReckoning {
  OdometryParams params;
  bool tyre_model{};  // vehicle.yaml's tyre model applied
  Pose2 start;
  std::string start_from;  // "truth" or "gnss"
  std::string reference_name;
  TrajectoryErrors errors;
  double distance_m{};  // odometry while moving (the one distance figure)
  double duration_s{};
  std::size_t wheel_samples{};
  LogPreparation prepared;
};

// The tyre model dead reckoning applies: vehicle.yaml's, unless options.plain.
TyreModel dead_reckoning_tyre_model(const LogDeadReckoningOptions& options,
                                    const VehicleConfig& vehicle);

// `on_pose` receives every pose of the trajectory in time order.
LogDeadReckoning dead_reckon_log(LogBlockSource& source, const LogDeadReckoningOptions& options,
                                 const std::function<void(double, const Pose2&)>& on_pose);

}  // namespace odocal
