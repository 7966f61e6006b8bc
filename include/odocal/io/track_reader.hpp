#pragma once
// Track centrelines in the TUMFTM racetrack-database format: "# x_m,y_m,w_tr_right_m,w_tr_left_m".

#include <Eigen/Core>
#include <filesystem>
#include <vector>

#include "odocal/io/csv_table.hpp"

namespace odocal {

// Reads the x_m, y_m columns (the widths are accepted and ignored). Throws InputError.
std::vector<Eigen::Vector2d> read_track_centreline(const std::filesystem::path& path);
// The same from a table already parsed (with header_may_be_comment).
std::vector<Eigen::Vector2d> track_centreline_from_table(const CsvTable& table);

}  // namespace odocal
