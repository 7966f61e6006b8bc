#pragma once
// The input mistakes the doctor must find (issue 16), each as a change to a clean simulated log
// directory, with the simulate flags it needs and the check that must name it. Shared by the
// doctor's tests and the full matrix over scenarios and seeds (bench/doctor_matrix.cpp).

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "odocal/estimation/log_diagnosis.hpp"

namespace odocal::testing {

using Row = std::map<std::string, double>;

// Rewrites a CSV file row by row (every column as a number); `header` renames the columns.
void edit_csv(const std::filesystem::path& file, const std::function<void(Row&)>& edit,
              std::vector<std::string> header = {});

// Leaves out the rows of a CSV file whose time (its first column) lies in [from_s, to_s).
void drop_rows_between(const std::filesystem::path& file, double from_s, double to_s);

struct Fault {
  const char* name;
  const char* simulate;  // extra simulate flags
  std::function<void(const std::filesystem::path&)> inject;
  const char* expected_check;
  // What the check says of it: most mistakes block a calibration; gaps, a stream that stops
  // early, denormal values, standstill biases and a missing altitude are warnings or notes.
  FindingSeverity expected_severity = FindingSeverity::kBlocking;
};

// What `odocal doctor` reports on a log directory: its findings, or, when the log does not read
// (garbage cells), the raw files' findings it prints before the reader's error.
Diagnosis doctor_directory(const std::filesystem::path& log);

// Found: the doctor reports the fault's check with its severity.
bool found(const Diagnosis& diagnosis, const Fault& fault);

// Simulate flags of the clean logs: a receiver that reports its altitude (a log without it gets
// the doctor's gnss.altitude note, which is one of the faults).
inline constexpr const char* kCleanLogFlags = "--gnss-altitude always";

std::vector<Fault> faults();

}  // namespace odocal::testing
