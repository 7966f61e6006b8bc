#pragma once
// A time window of a log: every stream cut to [from_s, to_s] (seconds on the log's clock), for
// `--from` / `--to` and for starting at the first motion.

#include "odocal/data/log.hpp"

namespace odocal {

// Throws InsufficientDataError when the window keeps fewer than 2 wheel samples or no GNSS fix.
// The first kept wheel sample gets a zero increment (it starts the chain).
Log crop_log(const Log& log, double from_s, double to_s);

}  // namespace odocal
