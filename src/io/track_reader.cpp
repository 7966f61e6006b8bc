#include "odocal/io/track_reader.hpp"

#include "odocal/io/csv_table.hpp"
#include "table_checks.hpp"

namespace odocal {

std::vector<Eigen::Vector2d> read_track_centreline(const std::filesystem::path& path) {
  const CsvTable table = read_csv_table(path, {.header_may_be_comment = true});
  detail::require_known_columns(table, {"x_m", "y_m", "w_tr_right_m", "w_tr_left_m"});
  detail::require_rows(table, 8, "a closed centreline needs at least 8 points");
  const std::vector<double>& x = table.column("x_m");
  const std::vector<double>& y = table.column("y_m");
  std::vector<Eigen::Vector2d> points;
  points.reserve(table.rows());
  for (std::size_t k = 0; k < table.rows(); ++k) points.emplace_back(x[k], y[k]);
  return points;
}

}  // namespace odocal
