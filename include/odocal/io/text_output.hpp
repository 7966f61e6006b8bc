#pragma once
// Text outputs formatted with fmt into memory and written whole through write_output_file
// (atomic; a failure is an OutputError naming the file). Needs fmt, a public dependency of the
// odocal package.

#include <fmt/format.h>

#include <filesystem>
#include <iterator>
#include <string_view>
#include <utility>

#include "odocal/io/output_file.hpp"

namespace odocal {

class TextBuffer {
 public:
  template <typename... Args>
  void print(fmt::format_string<Args...> format, Args&&... args) {
    fmt::format_to(std::back_inserter(buffer_), format, std::forward<Args>(args)...);
  }
  std::string_view view() const { return {buffer_.data(), buffer_.size()}; }

 private:
  fmt::memory_buffer buffer_;
};

// Calls write_text(TextBuffer&), then writes what it printed to `path`.
template <typename WriteText>
void write_text_file(const std::filesystem::path& path, WriteText&& write_text) {
  TextBuffer out;
  std::forward<WriteText>(write_text)(out);
  write_output_file(path, out.view());
}

}  // namespace odocal
