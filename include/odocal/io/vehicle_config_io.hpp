#pragma once
// vehicle.yaml: the nominal vehicle description (docs/log-format.md).

#include <filesystem>

#include "odocal/data/log.hpp"

namespace odocal {

// Throws InputError naming file, line and key for a missing/unknown key or a bad value.
VehicleConfig read_vehicle_config(const std::filesystem::path& path);
void write_vehicle_config(const VehicleConfig& vehicle, const std::filesystem::path& path);

}  // namespace odocal
