#pragma once
// A time window of a log: every stream cut to [from_s, to_s] (seconds on the log's clock), for
// `--from` / `--to` and for starting at the first motion.

#include "odocal/data/log.hpp"

namespace odocal {

// Throws InsufficientDataError when the window keeps fewer than 2 wheel samples or no GNSS fix.
// The first kept wheel sample gets a zero increment (it starts the chain).
Log crop_log(const Log& log, double from_s, double to_s);

// Every stream's samples with from_s <= t <= to_s, nothing else changed: the first wheel sample
// keeps its increment (a piece of a longer log, where the chain goes on).
Log slice_log(const Log& log, double from_s, double to_s);

// The first wheel sample starts the odometry chain: a zero increment, no break.
void start_wheel_chain(WheelStream& wheels);

// crop_log's checks, for a window read in pieces: at least 2 wheel samples and one GNSS fix.
void require_window_holds(std::size_t wheel_samples, std::size_t gnss_fixes, double from_s,
                          double to_s, double wheels_first_s, double wheels_last_s);

}  // namespace odocal
