#pragma once
// Every file odocal reads comes in through here: it must be a regular file (a directory, a FIFO
// or a device such as /dev/zero is refused instead of blocking or filling memory), not larger
// than max_bytes, and readable; each refusal is an InputError naming the file.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace odocal {

// 1 GiB: far beyond any log file odocal reads whole.
inline constexpr std::uintmax_t kMaxInputFileBytes = std::uintmax_t{1} << 30;

std::string read_input_file(const std::filesystem::path& path,
                            std::uintmax_t max_bytes = kMaxInputFileBytes);

// The same checks: the size of a readable regular file.
std::uintmax_t input_file_size(const std::filesystem::path& path);

// The same checks, then the file opened for reading as a stream of any length (a log streamed in
// chunks).
std::ifstream open_input_stream(const std::filesystem::path& path);

// Whether `path` names something (following symbolic links); a loop of links or a permission
// problem is an InputError, not "absent".
bool input_exists(const std::filesystem::path& path);

}  // namespace odocal
