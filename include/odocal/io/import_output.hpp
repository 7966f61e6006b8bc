#pragma once
// What every importer (CSV column map, ROS bag topic map) shares at its end: writing one stream
// file of the log, reading the staged log back as any log would be read, and the summary it
// prints.

#include <fmt/format.h>

#include <filesystem>
#include <string>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/io/output_file.hpp"

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

// One stream file of a log written a row at a time: `header`, then each row's time and values,
// value c with `decimals[c]` places. Nothing appears at `path` until commit().
class StreamCsvWriter {
 public:
  StreamCsvWriter(const std::filesystem::path& path, const std::string& header,
                  std::vector<int> decimals);
  void add(double t_s, const double* values);
  std::size_t rows() const { return rows_; }
  void commit();

 private:
  void flush();
  OutputFileStream out_;
  std::vector<int> decimals_;
  fmt::memory_buffer buffer_;
  std::size_t rows_{};
};

// Writes `header`, then t_s[k] and each column's value at the rows `rows`, `decimals[c]` places.
void write_stream_csv(const std::filesystem::path& path, const std::string& header,
                      const std::vector<double>& t_s,
                      const std::vector<const std::vector<double>*>& columns,
                      const std::vector<std::size_t>& rows, const std::vector<int>& decimals);

// Reads the staged log back as any log is read (a block at a time, holding none of it whole) and
// summarises it. An error names the file as it will be called in `target` and says that nothing
// was written.
ImportSummary check_staged_import(const std::filesystem::path& staged,
                                  const std::filesystem::path& target);

}  // namespace odocal
