#pragma once
// What every importer (CSV column map, ROS bag topic map) shares at its end: writing one stream
// file of the log, reading the staged log back as any log would be read, and the summary it
// prints.

#include <filesystem>
#include <string>
#include <vector>

#include "odocal/data/log.hpp"

namespace odocal {

struct ImportedStreamSummary {
  std::string name;  // wheels, gnss, imu, heading, truth
  std::size_t rows{};
  double start_s{};
  double duration_s{};
  double median_rate_hz{};
  double largest_gap_s{};
};

struct ImportSummary {
  std::vector<ImportedStreamSummary> streams;
  double wheel_distance_m{};  // while moving, rear wheels, nominal circumferences (motion_coverage)
  std::vector<std::string> notes;  // what the importer dropped or assumed, one line each
  // What a user should look at before calibrating (many rows dropped, a stream covering little
  // of the log), one line each; the CLI prints them on stderr.
  std::vector<std::string> warnings;
};

// Writes `header`, then t_s[k] and each column's value at the rows `rows`, `decimals[c]` places.
void write_stream_csv(const std::filesystem::path& path, const std::string& header,
                      const std::vector<double>& t_s,
                      const std::vector<const std::vector<double>*>& columns,
                      const std::vector<std::size_t>& rows, const std::vector<int>& decimals);

// Reads the staged log back (read_log) and summarises it. An error names the file as it will be
// called in `target` and says that nothing was written.
ImportSummary check_staged_import(const std::filesystem::path& staged,
                                  const std::filesystem::path& target);

}  // namespace odocal
