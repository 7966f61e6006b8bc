#pragma once
// Exit statuses of the odocal CLI (documented in README.md).

namespace odocal::cli {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;          // internal error, cannot write output, ...
constexpr int kExitBadInput = 2;         // malformed input or command line
constexpr int kExitNotIdentifiable = 3;  // well-formed data that cannot answer the question

}  // namespace odocal::cli
