#pragma once
// Reads a log directory in odocal's format (docs/log-format.md) into the neutral Log.

#include <filesystem>

#include "odocal/data/log.hpp"
#include "odocal/io/stream_readers.hpp"

namespace odocal {

struct LogReadOptions {
  WheelReadOptions wheels;
  bool read_truth = true;  // truth.csv is for evaluation only
};

// Throws InputError (file, line, column, what was expected) for anything malformed, including
// streams that do not overlap the wheel time span.
Log read_log(const std::filesystem::path& directory, const LogReadOptions& options = {});

}  // namespace odocal
