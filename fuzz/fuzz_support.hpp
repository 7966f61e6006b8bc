#pragma once
// What every harness shares: the contract under test is that bad input ends in an odocal::Error
// (InputError, InsufficientDataError, ...), never in a crash, another exception, a hang or a
// result that is not finite. An odocal::Error is swallowed; anything else reaches libFuzzer as a
// finding (an uncaught exception aborts).

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "odocal/error.hpp"

namespace odocal::fuzz {

inline std::string_view as_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

template <typename Body>
void expect_only_odocal_errors(Body&& body) {
  try {
    body();
  } catch (const odocal::Error&) {
    // The documented outcome for bad input.
  }
}

// A property the output must have whatever the input: a violation is a finding.
inline void require(bool property) {
  if (!property) std::abort();
}

// Parts of an input separated by a line "#--" (a harness that needs several files).
std::vector<std::string_view> split_parts(std::string_view text, std::size_t max_parts);

// A directory of this process for files a reader must find on disk (in memory when /dev/shm
// exists).
const std::filesystem::path& scratch_directory();

void write_file(const std::filesystem::path& path, std::string_view contents);

}  // namespace odocal::fuzz
