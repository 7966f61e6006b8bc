#pragma once
// Errors thrown by the odocal library. The library never exits the process: the CLI maps
// InputError to exit status 2, InsufficientDataError to 3 and anything else (OutputError among
// them) to 1.

#include <cstddef>
#include <stdexcept>
#include <string>

namespace odocal {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Where in an input a problem was found. Empty/zero members are left out of the message.
struct InputLocation {
  std::string file;    // path as given by the user
  std::size_t line{};  // 1-based; 0 = whole file
  std::string field;   // column name or YAML key
};

// Bad input: missing/malformed files, non-finite numbers, non-increasing time, ...
// what() is one line: "<file>:<line>: column '<field>': <problem>".
class InputError : public Error {
 public:
  InputError(InputLocation location, const std::string& problem);
  const InputLocation& location() const { return location_; }
  const std::string& problem() const { return problem_; }

 private:
  InputLocation location_;
  std::string problem_;
};

// Well-formed data that cannot determine what was asked (the vehicle barely moves, no heading
// reference where one is needed, too short). The CLI maps it to exit status 3.
class InsufficientDataError : public Error {
 public:
  using Error::Error;
};

// An output file could not be written; what() names the path and the system's reason.
class OutputError : public Error {
 public:
  using Error::Error;
};

}  // namespace odocal
