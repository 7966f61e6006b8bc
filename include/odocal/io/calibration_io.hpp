#pragma once
// The calibration config as YAML (`odocal calibrate --config FILE.yaml`, `--print-config`) and
// JSON, and a calibration summary as JSON (`--json`). The config's layout is
// for_each_config_section (odocal/estimation/calibration.hpp); each field's key, range and doc
// come from its options struct's table.

#include <nlohmann/json_fwd.hpp>
#include <string>

#include "odocal/estimation/calibration.hpp"

namespace odocal {

// Every key optional; unknown keys and bad values are InputErrors naming file, line and key.
CalibrationConfig parse_calibration_config(const std::string& yaml_text, const std::string& file,
                                           CalibrationConfig defaults = {});
CalibrationConfig read_calibration_config(const std::string& path, CalibrationConfig defaults = {});

nlohmann::json config_to_json(const CalibrationConfig& config);
// Commented YAML with every key: unit, range and a line of doc each. Parsed back, it gives
// `config` exactly.
std::string config_to_yaml(const CalibrationConfig& config);

// The summary of any method, with `termination`, `usable` and `message`, and the configuration
// it ran with.
nlohmann::json summary_to_json(const AnyCalibrationSummary& summary,
                               const CalibrationConfig& config);

}  // namespace odocal
