#include "odocal/io/input_file.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <system_error>

#include "odocal/error.hpp"

namespace odocal {
namespace {

namespace fs = std::filesystem;

fs::file_status status_of(const fs::path& path) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (error && error != std::errc::no_such_file_or_directory)
    throw InputError({path.string(), 0, ""}, "cannot open: " + error.message());
  return status;
}

}  // namespace

bool input_exists(const fs::path& path) { return fs::exists(status_of(path)); }

std::uintmax_t input_file_size(const fs::path& path) {
  const fs::file_status status = status_of(path);
  if (!fs::exists(status)) throw InputError({path.string(), 0, ""}, "cannot open: no such file");
  if (fs::is_directory(status))
    throw InputError({path.string(), 0, ""}, "is a directory, expected a file");
  if (!fs::is_regular_file(status))
    throw InputError({path.string(), 0, ""}, "not a regular file (a device, FIFO or socket)");
  std::error_code error;
  const std::uintmax_t bytes = fs::file_size(path, error);
  if (error) throw InputError({path.string(), 0, ""}, "cannot open: " + error.message());
  return bytes;
}

std::ifstream open_input_stream(const fs::path& path) {
  input_file_size(path);
  std::ifstream stream(path, std::ios::binary);
  if (!stream) throw InputError({path.string(), 0, ""}, "cannot open file");
  return stream;
}

std::string read_input_file(const fs::path& path, std::uintmax_t max_bytes) {
  const std::uintmax_t bytes = input_file_size(path);
  if (bytes > max_bytes) {
    throw InputError(
        {path.string(), 0, ""},
        fmt::format("{} bytes: larger than the {} bytes odocal reads", bytes, max_bytes));
  }
  std::ifstream stream = open_input_stream(path);
  std::ostringstream contents;
  contents << stream.rdbuf();
  if (stream.bad()) throw InputError({path.string(), 0, ""}, "cannot read file");
  return std::move(contents).str();
}

}  // namespace odocal
