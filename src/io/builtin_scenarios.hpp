#pragma once
// The scenario YAML files of config/scenarios/, compiled in (generated builtin_scenarios.cpp).

#include <string_view>
#include <vector>

namespace odocal::detail {

struct BuiltinScenario {
  std::string_view name;
  std::string_view yaml;
};

const std::vector<BuiltinScenario>& builtin_scenarios();

}  // namespace odocal::detail
