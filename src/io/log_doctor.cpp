#include "odocal/io/log_doctor.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "odocal/error.hpp"
#include "odocal/io/csv_table.hpp"
#include "odocal/io/input_file.hpp"
#include "odocal/io/log_reader.hpp"

namespace odocal {
namespace {

// A heading column whose values go beyond one turn in radians holds degrees.
void check_heading_unit(const std::filesystem::path& file, Diagnosis& diagnosis) {
  if (!input_exists(file)) return;
  const CsvTable table = read_csv_table(file);
  const auto& heading = table.column("heading");
  double largest = 0.0;
  for (const double value : heading) largest = std::max(largest, std::abs(value));
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
Log read_for_diagnosis(const std::filesystem::path& log_dir) {
  LogReadOptions options;
  options.read_truth = false;
  try {
    return read_log(log_dir, options);
  } catch (const InputError& error) {
    const std::string& field = error.location().field;
    if (!(field.ends_with("_rad") || field.ends_with("_radps") || field.ends_with("_mps"))) throw;
    options.wheels.max_wheel_speed_mps = 1e4;
    try {
      return read_log(log_dir, options);
    } catch (const InputError&) {
      throw error;
    }
  }
}

void scan_file(const std::filesystem::path& file, std::vector<Finding>& out) {
  if (!input_exists(file)) return;
  CsvOptions options;
  options.bad_numbers_as_nan = true;
  CsvTable table;
  try {
    table = read_csv_table(file, options);
  } catch (const InputError&) {
    return;  // not a table at all: the reader's own error says where
  }
  const std::string name = file.filename().string();
  for (std::size_t c = 0; c < table.header.size(); ++c) {
    std::size_t bad = 0, denormal = 0, first_bad = 0, first_denormal = 0;
    for (std::size_t row = 0; row < table.rows(); ++row) {
      const double value = table.columns[c][row];
      if (!std::isfinite(value)) {
        if (bad++ == 0) first_bad = table.line_of_row[row];
      } else if (std::fpclassify(value) == FP_SUBNORMAL) {
        if (denormal++ == 0) first_denormal = table.line_of_row[row];
      }
    }
    const std::string& column = table.header[c];
    if (bad > 0) {
      out.push_back(
          {"data.not_finite", FindingSeverity::kBlocking,
           fmt::format("{} column '{}' has {} cell(s) that are not finite numbers", name, column,
                       bad),
           fmt::format("{} of {} rows, the first at line {}", bad, table.rows(), first_bad),
           "a logger writing NaN, inf or text for missing values",
           "drop those rows, or leave the column out if it is optional"});
    }
    if (denormal > 0) {
      out.push_back({"data.denormal", FindingSeverity::kWarning,
                     fmt::format("{} column '{}' has {} denormal value(s)", name, column, denormal),
                     fmt::format("{} of {} rows below 2.2e-308 in magnitude, the first at line {}",
                                 denormal, table.rows(), first_denormal),
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

Diagnosis doctor_log(const std::filesystem::path& log_dir) {
  return doctor_log(read_for_diagnosis(log_dir), log_dir);
}

Diagnosis doctor_log(const Log& log, const std::filesystem::path& log_dir) {
  Diagnosis diagnosis = diagnose_log(log);
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

}  // namespace odocal
