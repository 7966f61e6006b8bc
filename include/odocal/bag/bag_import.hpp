#pragma once
// Importing a ROS bag through a YAML topic map (docs/importing.md, "ROS bags"): which topic feeds
// each stream, header stamp or record time, the IMU's mounting, the wheel joints or the twist
// fields, units and scales. Writes a log directory in odocal's format, whole or not at all, and
// validates it by reading it back.

#include <filesystem>

#include "odocal/io/import_output.hpp"

namespace odocal::bag {

// Throws InputError naming the map key, or the bag file and topic, for every problem.
ImportSummary import_bag(const std::filesystem::path& map_file,
                         const std::filesystem::path& bag_path,
                         const std::filesystem::path& out_dir);

}  // namespace odocal::bag
