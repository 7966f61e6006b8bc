#pragma once
// Runs the built odocal executable and captures its exit status, stdout and stderr.

#include <string>

namespace odocal::testing {

struct CliRun {
  int status{};
  std::string out;
  std::string err;
};

// `arguments` is appended to the executable path as given (shell syntax).
CliRun run_cli(const std::string& arguments);

std::string read_text_file(const std::string& path);

}  // namespace odocal::testing
