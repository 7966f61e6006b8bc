#pragma once
// Writes a text file through fmt, turning I/O failures into odocal::Error naming the file.

#include <fmt/os.h>

#include <filesystem>
#include <system_error>

#include "odocal/error.hpp"

namespace odocal::detail {

template <typename WriteRows>
void write_text_file(const std::filesystem::path& path, WriteRows&& write_rows) {
  try {
    auto out = fmt::output_file(path.string());
    write_rows(out);
    out.close();
  } catch (const std::system_error& e) {
    throw Error("cannot write " + path.string() + ": " + e.code().message());
  }
}

}  // namespace odocal::detail
