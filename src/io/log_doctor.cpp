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

}  // namespace

Diagnosis doctor_log(const std::filesystem::path& log_dir) {
  return doctor_log(read_for_diagnosis(log_dir), log_dir);
}

Diagnosis doctor_log(const Log& log, const std::filesystem::path& log_dir) {
  Diagnosis diagnosis = diagnose_log(log);
  check_heading_unit(log_dir / "heading.csv", diagnosis);
  // The degree values confuse the heading-rate comparison: one finding says it.
  if (std::any_of(diagnosis.findings.begin(), diagnosis.findings.end(),
                  [](const Finding& f) { return f.check == "heading.degrees"; })) {
    std::erase_if(diagnosis.findings,
                  [](const Finding& f) { return f.check == "heading.convention"; });
  }
  return diagnosis;
}

}  // namespace odocal
