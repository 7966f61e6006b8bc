#pragma once
// Importing any CSV logger through a YAML column map (docs/importing.md): which file and column
// holds each value, in which unit, time unit and offset, IMU frame, heading convention, and
// position kind. Writes a log directory in odocal's format and validates it by reading it back.

#include <filesystem>
#include <string>
#include <vector>

#include "odocal/io/import_output.hpp"

namespace odocal {

// `source_dir` holds the logger's files (relative paths in the map are resolved against it).
// Throws InputError naming the map key, or the file, line and column, for every problem.
ImportSummary import_csv(const std::filesystem::path& map_file,
                         const std::filesystem::path& source_dir,
                         const std::filesystem::path& out_dir);

}  // namespace odocal
