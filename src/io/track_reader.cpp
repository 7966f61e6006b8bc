#include "odocal/io/track_reader.hpp"

#include <fmt/format.h>

#include <cmath>

#include "odocal/error.hpp"
#include "odocal/io/csv_table.hpp"
#include "table_checks.hpp"

namespace odocal {
namespace {

constexpr double kMaxCentrelineStepM = 1000.0;

// Without overflow for coordinates near the largest double.
double step_m(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::hypot(a.x() - b.x(), a.y() - b.y());
}

}  // namespace

std::vector<Eigen::Vector2d> read_track_centreline(const std::filesystem::path& path) {
  return track_centreline_from_table(read_csv_table(path, {.header_may_be_comment = true}));
}

std::vector<Eigen::Vector2d> track_centreline_from_table(const CsvTable& table) {
  detail::require_known_columns(table, {"x_m", "y_m", "w_tr_right_m", "w_tr_left_m"});
  detail::require_rows(table, 8, "a closed centreline needs at least 8 points");
  const std::vector<double>& x = table.column("x_m");
  const std::vector<double>& y = table.column("y_m");
  std::vector<Eigen::Vector2d> points;
  points.reserve(table.rows());
  for (std::size_t k = 0; k < table.rows(); ++k) {
    points.emplace_back(x[k], y[k]);
    // A centreline is sampled every few metres; one point kilometres away is a typo that would
    // add thousands of kilometres to the simulated drive.
    if (k > 0 && step_m(points[k], points[k - 1]) > kMaxCentrelineStepM) {
      throw InputError(table.at(k, "x_m"),
                       fmt::format("{:.4g} m from the previous point; a centreline's points are at "
                                   "most {:.0f} m apart",
                                   step_m(points[k], points[k - 1]), kMaxCentrelineStepM));
    }
  }
  return points;
}

}  // namespace odocal
