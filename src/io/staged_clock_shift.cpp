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
  // Two streaming passes, as shift_times: the times and the column's values first (all the
  // interpolation needs), then every row copied with the column's field replaced.
  std::size_t index = 0;
  std::vector<double> t, values;
  {
    std::ifstream in = open_input_stream(file);
    std::string line;
    if (!std::getline(in, line)) return;
    const std::vector<std::string_view> header = fields(line);
    const auto found = std::find(header.begin(), header.end(), column);
    if (found == header.end())
      throw InputError({file.string(), 1, column}, "no such column to move in time");
    index = static_cast<std::size_t>(found - header.begin());
    while (std::getline(in, line)) {
      if (line.empty()) continue;
      const std::vector<std::string_view> row = fields(line);
      t.push_back(std::stod(std::string(row.front())));
      values.push_back(std::stod(std::string(row.at(index))));
    }
  }
  if (t.empty()) return;
  std::ifstream in = open_input_stream(file);
  BufferedWriter out(file);
  std::string line;
  std::getline(in, line);
  fmt::format_to(std::back_inserter(out.buffer()), "{}\n", line);
  for (std::size_t k = 0; std::getline(in, line);) {
    if (line.empty()) continue;
    const std::vector<std::string_view> row = fields(line);
    const double at = std::clamp(t[k] + late_s, t.front(), t.back());
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (i > 0) out.buffer().push_back(',');
      if (i == index)
        fmt::format_to(std::back_inserter(out.buffer()), "{:.6g}",
                       interpolate_linear(t, values, at).value_or(values[k]));
      else
        out.buffer().append(row[i]);
    }
    out.buffer().push_back('\n');
    out.flush_if_full();
    ++k;
  }
  out.commit();
}

}  // namespace odocal::detail
