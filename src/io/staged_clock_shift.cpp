#include "staged_clock_shift.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string_view>
#include <vector>

#include "odocal/error.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/io/input_file.hpp"
#include "odocal/io/output_file.hpp"

namespace odocal::detail {
namespace {

// The staged files are written by odocal itself: plain comma-separated numbers.
std::vector<std::string_view> fields(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::size_t start = 0;;) {
    const std::size_t comma = line.find(',', start);
    out.push_back(line.substr(start, comma - start));
    if (comma == std::string_view::npos) return out;
    start = comma + 1;
  }
}

class BufferedWriter {
 public:
  explicit BufferedWriter(const std::filesystem::path& file) : out_(file) {}
  fmt::memory_buffer& buffer() { return buffer_; }
  void flush_if_full() {
    if (buffer_.size() < (std::size_t{1} << 20)) return;
    out_.write({buffer_.data(), buffer_.size()});
    buffer_.clear();
  }
  void commit() {
    out_.write({buffer_.data(), buffer_.size()});
    out_.commit();
  }

 private:
  OutputFileStream out_;
  fmt::memory_buffer buffer_;
};

}  // namespace

void shift_times(const std::filesystem::path& file, double shift_s) {
  std::ifstream in = open_input_stream(file);
  BufferedWriter out(file);
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (header || line.empty()) {
      fmt::format_to(std::back_inserter(out.buffer()), "{}\n", line);
      header = false;
    } else {
      const std::size_t comma = line.find(',');
      const double t = std::stod(line.substr(0, comma));
      fmt::format_to(
          std::back_inserter(out.buffer()), "{:.6f}{}\n", t + shift_s,
          comma == std::string::npos ? std::string_view{} : std::string_view(line).substr(comma));
    }
    out.flush_if_full();
  }
  out.commit();
}

void advance_column(const std::filesystem::path& file, const std::string& column, double late_s) {
  std::vector<std::string> lines;
  {
    std::ifstream in = open_input_stream(file);
    for (std::string line; std::getline(in, line);)
      if (!line.empty()) lines.push_back(std::move(line));
  }
  if (lines.size() < 2) return;
  const std::vector<std::string_view> header = fields(lines.front());
  const auto found = std::find(header.begin(), header.end(), column);
  if (found == header.end())
    throw InputError({file.string(), 1, column}, "no such column to move in time");
  const auto index = static_cast<std::size_t>(found - header.begin());
  std::vector<double> t, values;
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const std::vector<std::string_view> row = fields(lines[k]);
    t.push_back(std::stod(std::string(row.front())));
    values.push_back(std::stod(std::string(row.at(index))));
  }
  BufferedWriter out(file);
  fmt::format_to(std::back_inserter(out.buffer()), "{}\n", lines.front());
  for (std::size_t k = 1; k < lines.size(); ++k) {
    const std::vector<std::string_view> row = fields(lines[k]);
    const double at = std::clamp(t[k - 1] + late_s, t.front(), t.back());
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i > 0) out.buffer().push_back(',');
      if (i == index)
        fmt::format_to(std::back_inserter(out.buffer()), "{:.6g}",
                       interpolate_linear(t, values, at).value_or(values[k - 1]));
      else
        out.buffer().append(row[i]);
    }
    out.buffer().push_back('\n');
    out.flush_if_full();
  }
  out.commit();
}

}  // namespace odocal::detail
