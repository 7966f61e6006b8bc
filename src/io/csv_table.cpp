#include "odocal/io/csv_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "odocal/io/input_file.hpp"

namespace odocal {
namespace {

std::string_view trim(std::string_view text) {
  const auto is_space = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  return text;
}

// Splits on ',' and calls on_field(index, field) for each trimmed field; returns the count.
template <typename OnField>
std::size_t for_each_field(std::string_view line, OnField&& on_field) {
  std::size_t index = 0;
  while (true) {
    const std::size_t comma = line.find(',');
    on_field(index++, trim(line.substr(0, comma)));
    if (comma == std::string_view::npos) return index;
    line.remove_prefix(comma + 1);
  }
}

std::string describe_field(std::string_view field) {
  constexpr std::size_t kMaxShown = 40;
  if (field.size() > kMaxShown) return "'" + std::string(field.substr(0, kMaxShown)) + "...'";
  return "'" + std::string(field) + "'";
}

double parse_finite(std::string_view field, const InputLocation& location) {
  if (field.empty()) throw InputError(location, "expected a number, got an empty field");
  std::string_view digits = field;
  if (digits.front() == '+') digits.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error == std::errc::result_out_of_range) {
    throw InputError(location, "expected a finite number, got " + describe_field(field));
  }
  if (error != std::errc() || end != digits.data() + digits.size()) {
    throw InputError(location, "expected a number, got " + describe_field(field));
  }
  if (!std::isfinite(value)) {
    throw InputError(location, "expected a finite number, got " + describe_field(field));
  }
  return value;
}

}  // namespace

std::optional<std::size_t> CsvTable::find(std::string_view name) const {
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end()) return std::nullopt;
  return static_cast<std::size_t>(it - header.begin());
}

const std::vector<double>& CsvTable::column(std::string_view name) const {
  const auto index = find(name);
  if (!index) {
    throw InputError({file, 1, std::string(name)}, "required column is missing from the header");
  }
  return columns[*index];
}

InputLocation CsvTable::at(std::size_t row, std::string_view name) const {
  return {file, line_of_row.at(row), std::string(name)};
}

namespace detail {

// One table's lines, in order: the preamble and header first, then data rows appended to a
// table (the whole file's, or one chunk's).
class CsvLineParser {
 public:
  CsvLineParser(std::string file_label, const CsvOptions& options)
      : file_(std::move(file_label)), options_(options) {}

  bool have_header() const { return have_header_; }
  std::size_t next_line_number() const { return line_number_ + 1; }
  const std::vector<std::string>& header() const { return header_; }
  const std::string& file() const { return file_; }

  // A table with the header and no rows yet.
  CsvTable empty_table() const {
    CsvTable table;
    table.file = file_;
    table.header = header_;
    table.columns.resize(header_.size());
    return table;
  }

  // Reads one line (without its newline); data rows go into `table`. Returns whether a row was
  // added.
  bool add_line(std::string_view line, CsvTable& table) {
    ++line_number_;
    if (line_number_ == 1 && line.substr(0, 3) == "\xEF\xBB\xBF") line.remove_prefix(3);  // BOM
    if (line_number_ <= options_.skip_lines) return false;
    std::string_view content = trim(line);
    if (content.empty()) return false;
    if (options_.logger_dialect &&
        (content.front() == '#' || (!have_header_ && content.starts_with("sep=")))) {
      return false;
    }
    if (!have_header_) {
      read_header(content);
      table.header = header_;
      table.columns.resize(header_.size());
      return false;
    }
    add_row(content, table);
    return true;
  }

  void finish() const {
    if (!have_header_) throw InputError({file_, 0, ""}, "file is empty: expected a header row");
  }

 private:
  void read_header(std::string_view content) {
    if (options_.header_may_be_comment && content.front() == '#') content = trim(content.substr(1));
    std::vector<std::string_view> names;
    for_each_field(content, [&](std::size_t, std::string_view name) { names.push_back(name); });
    if (options_.logger_dialect) {
      while (names.size() > 1 && names.back().empty()) {
        names.pop_back();
        ++trailing_empty_;
      }
    }
    for (std::size_t index = 0; index < names.size(); ++index) {
      const std::string_view name = names[index];
      const InputLocation location{file_, line_number_, std::string(name)};
      if (name.empty()) {
        throw InputError({file_, line_number_, ""},
                         "header field " + std::to_string(index + 1) + " is empty");
      }
      if (std::find(header_.begin(), header_.end(), name) != header_.end())
        throw InputError(location, "column name appears twice in the header");
      header_.emplace_back(name);
    }
    have_header_ = true;
  }

  void add_row(std::string_view content, CsvTable& table) {
    bool extra_cell = false;
    const std::size_t fields =
        for_each_field(content, [&](std::size_t index, std::string_view field) {
          if (index >= header_.size()) {
            extra_cell = extra_cell || !field.empty();
            return;
          }
          const InputLocation location{file_, line_number_, header_[index]};
          if (!options_.bad_numbers_as_nan) {
            table.columns[index].push_back(parse_finite(field, location));
            return;
          }
          try {
            table.columns[index].push_back(parse_finite(field, location));
          } catch (const InputError&) {
            table.columns[index].push_back(std::numeric_limits<double>::quiet_NaN());
          }
        });
    const bool trailing_ok = trailing_empty_ > 0 && !extra_cell && fields >= header_.size() &&
                             fields <= header_.size() + trailing_empty_;
    if (fields != header_.size() && !trailing_ok) {
      throw InputError({file_, line_number_, ""}, "expected " + std::to_string(header_.size()) +
                                                      " fields as in the " + "header, got " +
                                                      std::to_string(fields));
    }
    table.line_of_row.push_back(line_number_);
  }

  std::string file_;
  CsvOptions options_;
  std::size_t line_number_ = 0;
  bool have_header_ = false;
  std::size_t trailing_empty_ = 0;  // logger dialect: empty header fields after the last name
  std::vector<std::string> header_;
};

}  // namespace detail

CsvTable parse_csv_table(std::string_view text, const std::string& file_label,
                         const CsvOptions& options) {
  detail::CsvLineParser parser(file_label, options);
  CsvTable table = parser.empty_table();
  while (!text.empty()) {
    const std::size_t newline = text.find('\n');
    parser.add_line(text.substr(0, newline), table);
    text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
  }
  parser.finish();
  return table;
}

CsvChunkReader::CsvChunkReader(const std::filesystem::path& path, const CsvOptions& options)
    : parser_(std::make_unique<detail::CsvLineParser>(path.string(), options)),
      stream_(open_input_stream(path)) {
  // A small file needs no megabyte of buffer (a fuzzer reads thousands of them a second).
  std::error_code error;
  const std::uintmax_t bytes = std::filesystem::file_size(path, error);
  buffer_.resize(error ? kReadBytes
                       : static_cast<std::size_t>(std::min<std::uintmax_t>(kReadBytes, bytes + 1)));
  // The header (and anything before it) comes with the first chunk's rows or alone.
  CsvTable none = parser_->empty_table();
  while (!parser_->have_header() && read_line()) parser_->add_line(line_, none);
  parser_->finish();
}

CsvChunkReader::~CsvChunkReader() = default;

const std::vector<std::string>& CsvChunkReader::header() const { return parser_->header(); }
const std::string& CsvChunkReader::file() const { return parser_->file(); }

std::optional<CsvTable> CsvChunkReader::next(std::size_t max_rows) {
  CsvTable table = parser_->empty_table();
  while (table.rows() < max_rows && read_line()) parser_->add_line(line_, table);
  if (table.rows() == 0) return std::nullopt;
  return table;
}

bool CsvChunkReader::read_line() {
  line_.clear();
  while (true) {
    if (position_ == filled_) {
      if (at_end_) return !line_.empty();
      stream_.read(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
      filled_ = static_cast<std::size_t>(stream_.gcount());
      position_ = 0;
      if (stream_.bad()) throw InputError({parser_->file(), 0, ""}, "cannot read file");
      if (filled_ < buffer_.size()) at_end_ = true;
      if (filled_ == 0) return !line_.empty();
    }
    const char* begin = buffer_.data() + position_;
    const auto* newline = static_cast<const char*>(std::memchr(begin, '\n', filled_ - position_));
    const std::size_t length =
        newline != nullptr ? static_cast<std::size_t>(newline - begin) : filled_ - position_;
    if (line_.size() + length > kMaxLineBytes) {
      throw InputError({parser_->file(), parser_->next_line_number(), ""},
                       fmt::format("a line longer than {} bytes: not a CSV log", kMaxLineBytes));
    }
    line_.append(begin, length);
    position_ += length;
    if (newline != nullptr) {
      ++position_;
      return true;
    }
  }
}

CsvTable read_csv_table(const std::filesystem::path& path, const CsvOptions& options) {
  if (const std::uintmax_t bytes = input_file_size(path); bytes > kMaxInputFileBytes) {
    throw InputError({path.string(), 0, ""},
                     fmt::format("{} bytes: larger than the {} bytes odocal reads whole", bytes,
                                 kMaxInputFileBytes));
  }
  CsvChunkReader reader(path, options);
  std::optional<CsvTable> table = reader.next(SIZE_MAX);
  if (!table) {
    CsvTable empty;
    empty.file = reader.file();
    empty.header = reader.header();
    empty.columns.resize(empty.header.size());
    return empty;
  }
  return std::move(*table);
}

}  // namespace odocal
