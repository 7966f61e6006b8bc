#pragma once
// The keys of vehicle.yaml, read from any YAML mapping (vehicle.yaml itself, or the `vehicle`
// section of an import map).

#include "odocal/data/log.hpp"
#include "yaml_map.hpp"

namespace odocal::detail {

VehicleConfig parse_vehicle_config(YamlMap& map);

}  // namespace odocal::detail
