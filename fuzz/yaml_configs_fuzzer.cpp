// Every YAML input: the first byte picks calibration options, vehicle.yaml or a scenario, the
// rest is the file. A parse ends in a configuration that validates, or in InputError.

#include "fuzz_support.hpp"
#include "io/vehicle_config_parse.hpp"
#include "io/yaml_map.hpp"
#include "odocal/data/physical_limits.hpp"
#include "odocal/io/calibration_io.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/sim/simulation_limits.hpp"

namespace {

using namespace odocal;

void parse(std::uint8_t kind, const std::string& text) {
  switch (kind % 3) {
    case 0: {
      const CalibrationConfig config = parse_calibration_config(text, "config.yaml");
      fuzz::require(config.validate().empty());
      break;
    }
    case 1: {
      detail::YamlMap map(detail::parse_yaml(text, "vehicle.yaml"), "vehicle.yaml", "");
      const VehicleConfig vehicle = detail::parse_vehicle_config(map);
      fuzz::require(kTrackWidthM.contains(vehicle.track_width_m) &&
                    kCircumferenceM.contains(vehicle.circumference_rl_m) &&
                    kCircumferenceM.contains(vehicle.circumference_rr_m));
      break;
    }
    default: {
      const sim::Scenario scenario = parse_scenario(text, "scenario.yaml");
      sim::check_route_size(scenario);  // what simulate checks before building anything
      break;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text(fuzz::as_text(data + 1, size - 1));
  fuzz::expect_only_odocal_errors([&] { parse(data[0], text); });
  return 0;
}
