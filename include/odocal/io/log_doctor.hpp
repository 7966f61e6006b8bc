#pragma once
// The doctor on a log directory: diagnose_log on the log as read, plus what only the raw files
// show (a heading column in degrees, which the reader wraps as radians).

#include <filesystem>

#include "odocal/estimation/log_diagnosis.hpp"

namespace odocal {

Diagnosis doctor_log(const std::filesystem::path& log_dir);
// The same for a log already read from `log_dir` (calibrate diagnoses the log it calibrates).
Diagnosis doctor_log(const Log& log, const std::filesystem::path& log_dir);

// Garbage in the raw stream files, counted per column with its first line: cells that are not
// finite numbers (`data.not_finite`, blocking: the reader refuses the file at the first) and
// denormal values (`data.denormal`, warning: uninitialised memory written out, which the reader
// takes for a number near zero). doctor_log includes it; the CLI runs it alone when the log does
// not read, so that the user sees every bad column at once.
std::vector<Finding> scan_stream_values(const std::filesystem::path& log_dir);

}  // namespace odocal
