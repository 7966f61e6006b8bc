#pragma once
// Importing any CSV logger through a YAML column map (docs/importing.md): which file and column
// holds each value, in which unit, time unit and offset, IMU frame, heading convention, and
// position kind. Writes a log directory in odocal's format and validates it by reading it back.

#include <filesystem>
#include <string>
#include <vector>

#include "odocal/io/import_output.hpp"

namespace odocal {

struct CsvImportOptions {
  // Estimate the GNSS and IMU clock offsets against the wheels as `odocal doctor` does (the
  // cross-correlation of yaw rates and speeds) and shift those streams by them, and the drive
  // force column's against the accelerometer; each applied offset is a note in the summary.
  bool sync_clocks = false;
};

// `source_dir` holds the logger's files (relative paths in the map are resolved against it).
// Throws InputError naming the map key, or the file, line and column, for every problem.
ImportSummary import_csv(const std::filesystem::path& map_file,
                         const std::filesystem::path& source_dir,
                         const std::filesystem::path& out_dir,
                         const CsvImportOptions& options = {});

}  // namespace odocal
