#include "odocal/io/csv_table.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
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

CsvTable parse_csv_table(std::string_view text, const std::string& file_label,
                         const CsvOptions& options) {
  CsvTable table;
  table.file = file_label;
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 byte-order mark

  std::size_t line_number = 0;
  bool have_header = false;
  std::size_t trailing_empty = 0;  // logger dialect: empty header fields after the last name
  while (!text.empty()) {
    const std::size_t newline = text.find('\n');
    const std::string_view line = text.substr(0, newline);
    text.remove_prefix(newline == std::string_view::npos ? text.size() : newline + 1);
    ++line_number;
    if (line_number <= options.skip_lines) continue;
    std::string_view content = trim(line);
    if (content.empty()) continue;
    if (options.logger_dialect &&
        (content.front() == '#' || (!have_header && content.starts_with("sep=")))) {
      continue;
    }

    if (!have_header) {
      if (options.header_may_be_comment && content.front() == '#') {
        content = trim(content.substr(1));
      }
      std::vector<std::string_view> names;
      for_each_field(content, [&](std::size_t, std::string_view name) { names.push_back(name); });
      if (options.logger_dialect) {
        while (names.size() > 1 && names.back().empty()) {
          names.pop_back();
          ++trailing_empty;
        }
      }
      for (std::size_t index = 0; index < names.size(); ++index) {
        const std::string_view name = names[index];
        const InputLocation location{file_label, line_number, std::string(name)};
        if (name.empty()) {
          throw InputError({file_label, line_number, ""},
                           "header field " + std::to_string(index + 1) + " is empty");
        }
        if (std::find(table.header.begin(), table.header.end(), name) != table.header.end()) {
          throw InputError(location, "column name appears twice in the header");
        }
        table.header.emplace_back(name);
      }
      table.columns.resize(table.header.size());
      have_header = true;
      continue;
    }

    bool extra_cell = false;
    const std::size_t fields =
        for_each_field(content, [&](std::size_t index, std::string_view field) {
          if (index >= table.header.size()) {
            extra_cell = extra_cell || !field.empty();
            return;
          }
          const InputLocation location{file_label, line_number, table.header[index]};
          if (!options.bad_numbers_as_nan) {
            table.columns[index].push_back(parse_finite(field, location));
            return;
          }
          try {
            table.columns[index].push_back(parse_finite(field, location));
          } catch (const InputError&) {
            table.columns[index].push_back(std::numeric_limits<double>::quiet_NaN());
          }
        });
    const bool trailing_ok = trailing_empty > 0 && !extra_cell && fields >= table.header.size() &&
                             fields <= table.header.size() + trailing_empty;
    if (fields != table.header.size() && !trailing_ok) {
      throw InputError({file_label, line_number, ""},
                       "expected " + std::to_string(table.header.size()) + " fields as in the " +
                           "header, got " + std::to_string(fields));
    }
    table.line_of_row.push_back(line_number);
  }
  if (!have_header) throw InputError({file_label, 0, ""}, "file is empty: expected a header row");
  return table;
}

CsvTable read_csv_table(const std::filesystem::path& path, const CsvOptions& options) {
  return parse_csv_table(read_input_file(path), path.string(), options);
}

}  // namespace odocal
