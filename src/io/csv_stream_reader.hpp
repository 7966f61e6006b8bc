#pragma once
// One stream of `odocal import csv` (docs/importing.md): the logger's files as they are (preamble
// lines, an Excel "sep=," line, comments, trailing commas, garbage cells), the stream's time base
// (any unit, scale and offset; rows repeated on named columns collapsed) and its value columns in
// SI units on that base (from its own file, or interpolated from another with its own clock).

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <initializer_list>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "odocal/io/csv_table.hpp"
#include "units.hpp"
#include "yaml_map.hpp"

namespace odocal::detail {

// Source tables, each read once, with the map's per-file options (`files: {NAME: {skip_lines}}`).
class TableCache {
 public:
  TableCache(std::filesystem::path source_dir, std::map<std::string, std::size_t> skip_lines)
      : source_dir_(std::move(source_dir)), skip_lines_(std::move(skip_lines)) {}
  const CsvTable& get(const std::string& file);

 private:
  std::filesystem::path source_dir_;
  std::map<std::string, std::size_t> skip_lines_;
  std::map<std::string, CsvTable> tables_;
};

// Rows left out of a stream, for the import's notes and warnings.
struct DroppedRows {
  std::size_t bad_values{};  // a time or used value that is not a finite number (bad_values: drop)
  std::size_t first_bad_line{};
  std::string first_bad_file;
  std::size_t repeated{};  // collapsed by `dedupe`
};

class StreamReader {
 public:
  // `node` is the stream's raw YAML (the map's view of it tracks which keys were read).
  StreamReader(YamlMap map, YAML::Node node, TableCache& cache);

  bool has(const std::string& key) const { return map_.has(key); }
  bool is_text(const std::string& key) const { return node_[key].IsScalar(); }
  YamlMap& map() { return map_; }
  const std::vector<double>& t_s() const { return t_s_; }
  // Rows of the stream's file before anything was left out.
  std::size_t source_rows() const { return source_rows_; }
  DroppedRows dropped() const;

  std::string text(const std::string& key, const std::string& fallback);

  // A value column in SI units on the stream's time base; `quantities` are the accepted kinds.
  // NaN where the value is missing (another file's span) or, with bad_values: drop, not finite.
  std::pair<std::vector<double>, Quantity> values(const std::string& key,
                                                  std::initializer_list<Quantity> quantities);

  void done() { map_.reject_unknown_keys(); }

 private:
  struct TimeSpec {
    std::string column;
    double to_si{1.0};
    double offset_s{};
    InputLocation where;  // the time section's column key, for errors
  };
  TimeSpec read_time_spec(YamlMap& time) const;
  // Times of `table`'s rows (NaN where not finite), checked to increase where finite.
  std::vector<double> times_of(const CsvTable& table, const TimeSpec& spec) const;
  void note_bad_time(const CsvTable& table, std::size_t row);

  YAML::Node node_;
  YamlMap map_;
  TableCache& cache_;
  std::string file_;
  TimeSpec time_;
  bool drop_bad_{};
  std::vector<std::size_t> rows_;  // the file's rows kept, in order
  std::vector<double> t_s_;
  std::size_t source_rows_{};
  DroppedRows dropped_;                  // by time and dedupe
  std::vector<std::uint8_t> value_bad_;  // per kept row: a used value is not finite
};

}  // namespace odocal::detail
