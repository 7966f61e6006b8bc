#pragma once
// Calibration options as YAML (`odocal calibrate --config FILE.yaml`) and results as JSON.

#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "odocal/estimation/calibration.hpp"

namespace odocal {

// Every key optional; unknown keys and bad values are InputErrors naming file, line and key.
CalibrationOptions parse_calibration_options(const std::string& yaml_text, const std::string& file,
                                             CalibrationOptions defaults = {});
CalibrationOptions read_calibration_options(const std::string& path,
                                            CalibrationOptions defaults = {});

nlohmann::json options_to_json(const CalibrationOptions& options);
nlohmann::json result_to_json(const CalibrationResult& result, const CalibrationOptions& options);

std::optional<CalibrationMethod> parse_method(const std::string& name);

}  // namespace odocal
