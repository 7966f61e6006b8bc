#pragma once
// A strict reader for numeric CSV files with a header row: every field must be a finite number,
// every row must have as many fields as the header. Errors name file, line and column.

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "odocal/error.hpp"

namespace odocal {

struct CsvTable {
  std::string file;  // label used in error messages
  std::vector<std::string> header;
  std::vector<std::vector<double>> columns;  // columns[c][row]
  std::vector<std::size_t> line_of_row;      // 1-based file line of each data row

  std::size_t rows() const { return line_of_row.size(); }
  std::optional<std::size_t> find(std::string_view name) const;
  bool has(std::string_view name) const { return find(name).has_value(); }
  // Throws InputError naming the file when the column is missing.
  const std::vector<double>& column(std::string_view name) const;
  // Location of a value, for messages about its content.
  InputLocation at(std::size_t row, std::string_view name) const;
};

struct CsvOptions {
  // Accept a header written as a comment ("# x_m,y_m,..."), as in the TUMFTM track database.
  bool header_may_be_comment = false;
  // Keep a cell that is not a finite number as NaN instead of refusing the file (the doctor's
  // count of garbage values); rows with the wrong number of fields are still refused.
  bool bad_numbers_as_nan = false;
  // Loggers as they are (odocal import csv): lines before the header to skip; an Excel "sep=,"
  // first line, comment lines starting with '#' and trailing empty header fields (a trailing
  // comma, whose cells must then be empty) are accepted.
  std::size_t skip_lines = 0;
  bool logger_dialect = false;
};

CsvTable parse_csv_table(std::string_view text, const std::string& file_label,
                         const CsvOptions& options = {});
// Throws InputError when the file is missing or unreadable, larger than kMaxInputFileBytes, or
// on any malformed content.
CsvTable read_csv_table(const std::filesystem::path& path, const CsvOptions& options = {});

namespace detail {
class CsvLineParser;
}

// Reads a CSV file a piece at a time, so that a log of any length streams through bounded
// memory: each chunk is a table of consecutive data rows with the file's header and their own
// line numbers, checked exactly as read_csv_table checks the whole file.
class CsvChunkReader {
 public:
  // Opens the file and reads up to its header (InputError when absent, not a regular file, or
  // without a header).
  explicit CsvChunkReader(const std::filesystem::path& path, const CsvOptions& options = {});
  ~CsvChunkReader();
  CsvChunkReader(const CsvChunkReader&) = delete;
  CsvChunkReader& operator=(const CsvChunkReader&) = delete;

  const std::vector<std::string>& header() const;
  const std::string& file() const;
  // The next at most max_rows data rows; nothing once the file is read.
  std::optional<CsvTable> next(std::size_t max_rows);

 private:
  static constexpr std::size_t kReadBytes = std::size_t{1} << 20;
  static constexpr std::size_t kMaxLineBytes = std::size_t{64} << 20;
  bool read_line();  // into line_; false at the end

  std::unique_ptr<detail::CsvLineParser> parser_;
  std::ifstream stream_;
  std::vector<char> buffer_;
  std::size_t position_ = 0, filled_ = 0;
  bool at_end_ = false;
  std::string line_;
};

}  // namespace odocal
