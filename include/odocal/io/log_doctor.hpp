#pragma once
// The doctor on a log directory: diagnose_log on the log as read, plus what only the raw files
// show (a heading column in degrees, which the reader wraps as radians).

#include <filesystem>

#include "odocal/estimation/log_diagnosis.hpp"

namespace odocal {

Diagnosis doctor_log(const std::filesystem::path& log_dir);
// The same for a log already read from `log_dir` (calibrate diagnoses the log it calibrates).
Diagnosis doctor_log(const Log& log, const std::filesystem::path& log_dir);

}  // namespace odocal
