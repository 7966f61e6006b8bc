#pragma once
// Simulation scenarios as YAML (config/scenarios/*.yaml, docs/simulator.md). The built-in ones are
// compiled into the library, so no file is needed at run time.

#include <filesystem>
#include <string>
#include <vector>

#include "odocal/sim/scenario.hpp"

namespace odocal {

std::vector<std::string> builtin_scenario_names();
// A built-in name ("circuit", "parking", "urban") or a path to a scenario YAML file.
sim::Scenario load_scenario(const std::string& name_or_file);
// Parses scenario YAML; `file` labels messages. Every key is optional: defaults fill the rest.
sim::Scenario parse_scenario(const std::string& yaml_text, const std::string& file);
// Replaces the scenario's route by one lap of a closed TUMFTM centreline (docs/simulator.md);
// laps stay. Returns the largest distance of a centreline point from the driven path (m).
double use_track_file(sim::Scenario& scenario, const std::filesystem::path& track_csv);

// The complete effective scenario, every knob written out (re-loadable by parse_scenario).
std::string scenario_to_yaml(const sim::Scenario& scenario);

}  // namespace odocal
