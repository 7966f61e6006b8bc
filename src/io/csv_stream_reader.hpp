#pragma once
// One stream of `odocal import csv` (docs/importing.md): the logger's files as they are (preamble
// lines, an Excel "sep=," line, comments, trailing commas, garbage cells), the stream's time base
// (any unit, scale and offset; rows repeated on named columns collapsed) and its value columns in
// SI units on that base (from its own file, or interpolated from another with its own clock).
// Read a chunk of rows at a time, so that a log of any length converts through bounded memory.

#include <yaml-cpp/yaml.h>

#include <deque>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "odocal/io/csv_table.hpp"
#include "units.hpp"
#include "yaml_map.hpp"

namespace odocal::detail {

// Where the logger's files are, and the map's per-file options (`files: {NAME: {skip_lines}}`).
class SourceFiles {
 public:
  SourceFiles(std::filesystem::path source_dir, std::map<std::string, std::size_t> skip_lines)
      : source_dir_(std::move(source_dir)), skip_lines_(std::move(skip_lines)) {}
  std::unique_ptr<CsvChunkReader> open(const std::string& file) const;

 private:
  std::filesystem::path source_dir_;
  std::map<std::string, std::size_t> skip_lines_;
};

// Rows left out of a stream, for the import's notes and warnings.
struct DroppedRows {
  std::size_t bad_values{};  // a time or used value that is not a finite number (bad_values: drop)
  std::size_t first_bad_line{};
  std::string first_bad_file;
  std::size_t repeated{};  // collapsed by `dedupe`
};

// Rows of a stream: times and each declared value (NaN where missing: another file's span, or a
// value that is not finite under bad_values: drop).
struct StreamChunk {
  std::vector<double> t_s;
  std::vector<std::vector<double>> values;
  std::size_t rows() const { return t_s.size(); }
};

struct TimeSpec {
  std::string column;
  double to_si{1.0};
  double offset_s{};
  InputLocation where;  // the time section's column key, for errors
};

class ResampledColumn;

class StreamReader {
 public:
  // `node` is the stream's raw YAML (the map's view of it tracks which keys were read).
  StreamReader(YamlMap map, YAML::Node node, const SourceFiles& files);
  ~StreamReader();
  StreamReader(StreamReader&&) noexcept;

  bool has(const std::string& key) const { return map_.has(key); }
  bool is_text(const std::string& key) const { return node_[key].IsScalar(); }
  YamlMap& map() { return map_; }
  std::string text(const std::string& key, const std::string& fallback);

  // Declares the value `key` (a {column, unit, scale, offset, file, time} map); `quantities` are
  // the accepted kinds. Its values come in StreamChunk::values at the returned index.
  std::pair<std::size_t, Quantity> add_value(const std::string& key,
                                             std::initializer_list<Quantity> quantities);
  void done() { map_.reject_unknown_keys(); }

  // The next chunk of rows; false once the stream's file is read.
  bool next(StreamChunk& chunk);

  // After the last chunk: rows of the stream's file, and what was left out of them.
  std::size_t source_rows() const { return source_rows_; }
  DroppedRows dropped() const { return dropped_; }

 private:
  struct OwnValue {
    std::size_t column{};
    std::string column_name, unit_name;
    double to_si{}, scale{}, offset{};
  };
  struct Value {
    OwnValue own;
    std::unique_ptr<ResampledColumn> other;  // set when the value comes from another file
  };
  void note_bad(const std::string& file, std::size_t line);

  YAML::Node node_;
  YamlMap map_;
  const SourceFiles& files_;
  std::string file_;
  TimeSpec time_;
  bool drop_bad_{};
  std::unique_ptr<CsvChunkReader> reader_;
  std::size_t time_column_{};
  std::vector<std::size_t> dedupe_columns_;
  std::vector<double> last_dedupe_;  // the kept row before, on the dedupe columns
  bool have_kept_{};
  double last_t_ = -INFINITY;
  std::size_t last_line_{};
  std::vector<Value> values_;
  std::size_t source_rows_{};
  DroppedRows dropped_;
};

}  // namespace odocal::detail
