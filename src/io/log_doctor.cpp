#include "odocal/io/log_doctor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "odocal/error.hpp"
#include "odocal/io/csv_table.hpp"
#include "odocal/io/input_file.hpp"
#include "odocal/io/log_block_reader.hpp"
#include "odocal/io/log_reader.hpp"

namespace odocal {
namespace {

constexpr std::size_t kChunkRows = std::size_t{1} << 16;

// A heading column whose values go beyond one turn in radians holds degrees.
void check_heading_unit(const std::filesystem::path& file, Diagnosis& diagnosis) {
  if (!input_exists(file)) return;
  CsvChunkReader reader(file);
  double largest = 0.0;
  while (const std::optional<CsvTable> chunk = reader.next(kChunkRows)) {
    for (const double value : chunk->column("heading"))
      largest = std::max(largest, std::abs(value));
  }
  if (largest > 2.0 * std::numbers::pi + 0.5 && largest <= 360.0) {
    diagnosis.findings.push_back(
        {"heading.degrees", FindingSeverity::kBlocking, "the heading column holds degrees",
         fmt::format("values up to {:.1f} in heading.csv, which is in radians", largest),
         "a heading logged in degrees", "convert heading.csv to radians (import map: unit: deg)"});
  }
}

// The reader refuses wheel speeds beyond 100 m/s as corrupt; a unit mistake (rpm read as rad/s)
// produces exactly that, and the doctor is there to name it: it reads such a log again with a
// wider bound (angles and rates only; counters keep theirs, which their wrap detection needs).
// The log is streamed a block at a time: the doctor holds its grid, not the log.
Diagnosis diagnose_directory(const std::filesystem::path& log_dir) {
  LogReadOptions options;
  options.read_truth = false;
  try {
    LogBlockReader reader(log_dir, options);
    return diagnose_log(reader);
  } catch (const InputError& error) {
    const std::string& field = error.location().field;
    if (!(field.ends_with("_rad") || field.ends_with("_radps") || field.ends_with("_mps"))) throw;
    options.wheels.max_wheel_speed_mps = 1e4;
    try {
      LogBlockReader reader(log_dir, options);
      return diagnose_log(reader);
    } catch (const InputError&) {
      throw error;
    }
  }
}

// Per column of a file: cells that are not finite numbers and denormal values, with the first
// line of each.
struct ColumnGarbage {
  std::size_t bad{}, denormal{}, first_bad{}, first_denormal{};
};

void scan_file(const std::filesystem::path& file, std::vector<Finding>& out) {
  if (!input_exists(file)) return;
  CsvOptions options;
  options.bad_numbers_as_nan = true;
  std::vector<ColumnGarbage> garbage;
  std::vector<std::string> header;
  std::size_t rows = 0;
  try {
    CsvChunkReader reader(file, options);
    header = reader.header();
    garbage.resize(header.size());
    while (const std::optional<CsvTable> chunk = reader.next(kChunkRows)) {
      rows += chunk->rows();
      for (std::size_t c = 0; c < header.size(); ++c) {
        ColumnGarbage& column = garbage[c];
        for (std::size_t row = 0; row < chunk->rows(); ++row) {
          const double value = chunk->columns[c][row];
          if (!std::isfinite(value)) {
            if (column.bad++ == 0) column.first_bad = chunk->line_of_row[row];
          } else if (std::fpclassify(value) == FP_SUBNORMAL) {
            if (column.denormal++ == 0) column.first_denormal = chunk->line_of_row[row];
          }
        }
      }
    }
  } catch (const InputError&) {
    return;  // not a table at all: the reader's own error says where
  }
  const std::string name = file.filename().string();
  for (std::size_t c = 0; c < header.size(); ++c) {
    const auto [bad, denormal, first_bad, first_denormal] = garbage[c];
    const std::string& column = header[c];
    if (bad > 0) {
      out.push_back({"data.not_finite", FindingSeverity::kBlocking,
                     fmt::format("{} column '{}' has {} cell(s) that are not finite numbers", name,
                                 column, bad),
                     fmt::format("{} of {} rows, the first at line {}", bad, rows, first_bad),
                     "a logger writing NaN, inf or text for missing values",
                     "drop those rows, or leave the column out if it is optional"});
    }
    if (denormal > 0) {
      out.push_back({"data.denormal", FindingSeverity::kWarning,
                     fmt::format("{} column '{}' has {} denormal value(s)", name, column, denormal),
                     fmt::format("{} of {} rows below 2.2e-308 in magnitude, the first at line {}",
                                 denormal, rows, first_denormal),
                     "uninitialised memory written as numbers", "drop those rows"});
    }
  }
}

}  // namespace

std::vector<Finding> scan_stream_values(const std::filesystem::path& log_dir) {
  std::vector<Finding> out;
  for (const char* file : {"wheels.csv", "gnss.csv", "imu.csv", "heading.csv"})
    scan_file(log_dir / file, out);
  return out;
}

namespace {

// What only the raw files show, added to a diagnosis of the log as read.
Diagnosis with_raw_file_checks(Diagnosis diagnosis, const std::filesystem::path& log_dir) {
  check_heading_unit(log_dir / "heading.csv", diagnosis);
  for (Finding& finding : scan_stream_values(log_dir))
    diagnosis.findings.push_back(std::move(finding));
  // The degree values confuse the heading-rate comparison: one finding says it.
  if (std::any_of(diagnosis.findings.begin(), diagnosis.findings.end(),
                  [](const Finding& f) { return f.check == "heading.degrees"; })) {
    std::erase_if(diagnosis.findings,
                  [](const Finding& f) { return f.check == "heading.convention"; });
  }
  return diagnosis;
}

}  // namespace

Diagnosis doctor_log(const std::filesystem::path& log_dir) {
  return with_raw_file_checks(diagnose_directory(log_dir), log_dir);
}

Diagnosis doctor_log(const Log& log, const std::filesystem::path& log_dir) {
  return with_raw_file_checks(diagnose_log(log), log_dir);
}

}  // namespace odocal
