#pragma once
// The input mistakes the doctor must find (issue 16), each as a change to a clean simulated log
// directory, with the simulate flags it needs and the check that must name it. Shared by the
// doctor's tests and the full matrix over scenarios and seeds (bench/doctor_matrix.cpp).

#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace odocal::testing {

using Row = std::map<std::string, double>;

// Rewrites a CSV file row by row (every column as a number); `header` renames the columns.
void edit_csv(const std::filesystem::path& file, const std::function<void(Row&)>& edit,
              std::vector<std::string> header = {});

struct Fault {
  const char* name;
  const char* simulate;  // extra simulate flags
  std::function<void(const std::filesystem::path&)> inject;
  const char* expected_check;
};

std::vector<Fault> faults();

}  // namespace odocal::testing
