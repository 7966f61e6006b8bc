#pragma once
// Exit statuses of the odocal CLI (documented in README.md).

#include <stdexcept>

namespace odocal::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;          // internal error, cannot write output, ...
constexpr int kExitBadInput = 2;         // malformed input or command line
constexpr int kExitNotIdentifiable = 3;  // well-formed data that cannot answer the question

// A command finished but its result must not be used (a calibration that did not converge, is
// not identified or makes no physical sense): exit 3 with the reason.
class NotUsableResult : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace odocal::cli
