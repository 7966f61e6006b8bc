#include "csv_stream_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "odocal/error.hpp"

namespace odocal::detail {
namespace {

constexpr std::size_t kChunkRows = std::size_t{1} << 16;

TimeSpec read_time_spec(YamlMap& time) {
  TimeSpec spec;
  std::string unit_name = "s";
  double scale = 1.0;
  time.read("column", spec.column);
  time.read("unit", unit_name);
  time.read("scale", scale, 1e-15, 1e15);
  time.read("offset_s", spec.offset_s, -1e12, 1e12);
  time.reject_unknown_keys();
  const auto unit = parse_unit(unit_name);
  if (!unit || unit->quantity != Quantity::kTime) {
    throw InputError(time.location("unit"),
                     "expected a time unit (" + unit_names(Quantity::kTime) + ")");
  }
  spec.to_si = unit->to_si * scale;
  spec.where = time.location("column");
  return spec;
}

std::size_t column_of(const CsvChunkReader& reader, const std::string& column,
                      const InputLocation& where) {
  const auto& header = reader.header();
  const auto at = std::find(header.begin(), header.end(), column);
  if (column.empty() || at == header.end())
    throw InputError(where, fmt::format("column '{}' is not in {}", column, reader.file()));
  return static_cast<std::size_t>(at - header.begin());
}

// A file's times in SI: a time that is not finite after the conversion is an error, or NaN under
// bad_values: drop; finite times must strictly increase (`last_t`, `last_line` carry that across
// chunks).
double converted_time(const CsvTable& chunk, std::size_t column, std::size_t row,
                      const TimeSpec& spec, bool drop_bad, double& last_t, std::size_t& last_line) {
  const double t = chunk.columns[column][row] * spec.to_si + spec.offset_s;
  const InputLocation at{chunk.file, chunk.line_of_row[row], spec.column};
  if (!std::isfinite(t)) {
    if (!drop_bad) {
      throw InputError(at,
                       "not a finite time after the unit conversion (bad_values: drop leaves "
                       "such rows out)");
    }
    return NAN;
  }
  if (!(t > last_t) && last_t > -INFINITY) {
    throw InputError(
        at, fmt::format("time must strictly increase (line {} has {:.9g} s)", last_line, last_t));
  }
  last_t = t;
  last_line = chunk.line_of_row[row];
  return t;
}

// A value in SI units: a finite cell that is not finite after the conversion is an error.
double converted_value(const CsvTable& chunk, std::size_t column, std::size_t row, double to_si,
                       double scale, double offset, const std::string& column_name,
                       const std::string& unit_name) {
  const double raw = chunk.columns[column][row];
  const double value = raw * to_si * scale + offset;
  if (std::isfinite(raw) && !std::isfinite(value)) {
    throw InputError({chunk.file, chunk.line_of_row[row], column_name},
                     fmt::format("{:g} {} is not a finite value in SI units", raw, unit_name));
  }
  return value;
}

[[noreturn]] void reject_bad(const CsvTable& chunk, std::size_t row, const std::string& column) {
  throw InputError({chunk.file, chunk.line_of_row[row], column},
                   "expected a finite number (bad_values: drop leaves such rows out)");
}

}  // namespace

std::unique_ptr<CsvChunkReader> SourceFiles::open(const std::string& file) const {
  CsvOptions options;
  options.logger_dialect = true;
  options.bad_numbers_as_nan = true;  // garbage in a column nobody uses must not matter
  if (const auto skip = skip_lines_.find(file); skip != skip_lines_.end())
    options.skip_lines = skip->second;
  return std::make_unique<CsvChunkReader>(source_dir_ / file, options);
}

// A value from another file of the same sensor: its finite samples on its own clock, interpolated
// onto the stream's times (NaN outside its span), read forward as the stream's times advance.
class ResampledColumn {
 public:
  ResampledColumn(std::unique_ptr<CsvChunkReader> reader, TimeSpec time, std::size_t column,
                  std::string column_name, double to_si, double scale, double offset,
                  std::string unit_name, bool drop_bad)
      : reader_(std::move(reader)),
        time_(std::move(time)),
        time_column_(column_of(*reader_, time_.column, time_.where)),
        column_(column),
        column_name_(std::move(column_name)),
        unit_name_(std::move(unit_name)),
        to_si_(to_si),
        scale_(scale),
        offset_(offset),
        drop_bad_(drop_bad) {}

  // The value at t; t never decreases from one call to the next.
  double at(double t) {
    while (!ended_ && (samples_.empty() || samples_.back().first < t)) read_chunk();
    while (samples_.size() >= 2 && samples_[1].first <= t) samples_.pop_front();
    if (samples_.empty() || t < samples_.front().first) return NAN;
    if (t == samples_.front().first) return samples_.front().second;
    if (samples_.size() < 2) return NAN;
    const auto& [t0, v0] = samples_[0];
    const auto& [t1, v1] = samples_[1];
    return v0 + (t - t0) / (t1 - t0) * (v1 - v0);
  }

 private:
  void read_chunk() {
    const std::optional<CsvTable> chunk = reader_->next(kChunkRows);
    if (!chunk) {
      ended_ = true;
      return;
    }
    for (std::size_t row = 0; row < chunk->rows(); ++row) {
      const double t =
          converted_time(*chunk, time_column_, row, time_, drop_bad_, last_t_, last_line_);
      const double v =
          converted_value(*chunk, column_, row, to_si_, scale_, offset_, column_name_, unit_name_);
      if (std::isnan(t) || !std::isfinite(v)) {
        if (!std::isnan(t) && !drop_bad_) reject_bad(*chunk, row, column_name_);
        continue;
      }
      samples_.emplace_back(t, v);
    }
  }

  std::unique_ptr<CsvChunkReader> reader_;
  TimeSpec time_;
  std::size_t time_column_, column_;
  std::string column_name_, unit_name_;
  double to_si_, scale_, offset_;
  bool drop_bad_;
  std::deque<std::pair<double, double>> samples_;
  bool ended_ = false;
  double last_t_ = -INFINITY;
  std::size_t last_line_{};
};

StreamReader::StreamReader(YamlMap map, YAML::Node node, const SourceFiles& files)
    : node_(std::move(node)), map_(std::move(map)), files_(files) {
  map_.read("file", file_);
  if (file_.empty())
    throw InputError(map_.location(), "'file' is required: the CSV that holds this stream");
  std::string bad_values = "reject";
  map_.read("bad_values", bad_values);
  if (bad_values != "reject" && bad_values != "drop")
    throw InputError(map_.location("bad_values"), "expected reject or drop");
  drop_bad_ = bad_values == "drop";
  auto time = map_.map("time");
  if (!time) throw InputError(map_.location(), "'time' is required: {column, unit, offset_s}");
  time_ = read_time_spec(*time);
  reader_ = files_.open(file_);
  time_column_ = column_of(*reader_, time_.column, time_.where);
  // dedupe: a row whose named columns all equal those of the row kept before it repeats it.
  for (const YAML::Node& name : map_.sequence("dedupe")) {
    const std::string column = name.IsScalar() ? name.Scalar() : "";
    dedupe_columns_.push_back(column_of(*reader_, column, map_.location("dedupe")));
  }
  last_dedupe_.resize(dedupe_columns_.size());
}

StreamReader::~StreamReader() = default;
StreamReader::StreamReader(StreamReader&&) noexcept = default;

std::string StreamReader::text(const std::string& key, const std::string& fallback) {
  std::string value = fallback;
  map_.read(key, value);
  return value;
}

std::pair<std::size_t, Quantity> StreamReader::add_value(
    const std::string& key, std::initializer_list<Quantity> quantities) {
  auto spec = map_.map(key);
  if (!spec) throw InputError(map_.location(), fmt::format("'{}' is required", key));
  std::string file = file_, column, unit_name;
  double scale = 1.0;  // -1: a column whose sign is reversed (an encoder counting backwards)
  double offset = 0.0;
  spec->read("file", file);
  spec->read("column", column);
  spec->read("unit", unit_name);
  spec->read("scale", scale, -1e6, 1e6);
  spec->read("offset", offset, -1e12, 1e12);
  if (scale == 0.0) throw InputError(spec->location("scale"), "must not be 0");
  // Another file keeps its own clock: its `time`, else the stream's.
  TimeSpec other_time = time_;
  if (auto time = spec->map("time")) other_time = read_time_spec(*time);
  spec->reject_unknown_keys();
  const auto unit = parse_unit(unit_name);
  if (!unit ||
      std::find(quantities.begin(), quantities.end(), unit->quantity) == quantities.end()) {
    std::string accepted;
    for (Quantity q : quantities) accepted += (accepted.empty() ? "" : ", ") + unit_names(q);
    throw InputError(spec->location("unit"), fmt::format("expected one of {}", accepted));
  }
  Value value;
  value.own = {0, column, unit_name, unit->to_si, scale, offset};
  if (file == file_) {
    value.own.column = column_of(*reader_, column, spec->location("column"));
  } else {
    std::unique_ptr<CsvChunkReader> other = files_.open(file);
    const std::size_t index = column_of(*other, column, spec->location("column"));
    value.other =
        std::make_unique<ResampledColumn>(std::move(other), other_time, index, column, unit->to_si,
                                          scale, offset, unit_name, drop_bad_);
  }
  values_.push_back(std::move(value));
  return {values_.size() - 1, unit->quantity};
}

void StreamReader::note_bad(const std::string& file, std::size_t line) {
  ++dropped_.bad_values;
  if (dropped_.first_bad_line == 0 || line < dropped_.first_bad_line) {
    dropped_.first_bad_line = line;
    dropped_.first_bad_file = file;
  }
}

bool StreamReader::next(StreamChunk& out) {
  out.t_s.clear();
  out.values.assign(values_.size(), {});
  while (out.rows() == 0) {
    const std::optional<CsvTable> chunk = reader_->next(kChunkRows);
    if (!chunk) return false;
    source_rows_ += chunk->rows();
    std::vector<std::size_t> rows;  // of the chunk, kept
    for (std::size_t row = 0; row < chunk->rows(); ++row) {
      const double t =
          converted_time(*chunk, time_column_, row, time_, drop_bad_, last_t_, last_line_);
      if (std::isnan(t)) {
        note_bad(chunk->file, chunk->line_of_row[row]);
        continue;
      }
      bool repeats = have_kept_ && !dedupe_columns_.empty();
      for (std::size_t d = 0; repeats && d < dedupe_columns_.size(); ++d)
        repeats = chunk->columns[dedupe_columns_[d]][row] == last_dedupe_[d];
      if (repeats) {
        ++dropped_.repeated;
        continue;
      }
      for (std::size_t d = 0; d < dedupe_columns_.size(); ++d)
        last_dedupe_[d] = chunk->columns[dedupe_columns_[d]][row];
      have_kept_ = true;
      rows.push_back(row);
      out.t_s.push_back(t);
    }
    std::vector<std::uint8_t> bad(rows.size(), 0);  // a used value is not finite
    for (std::size_t v = 0; v < values_.size(); ++v) {
      Value& value = values_[v];
      std::vector<double>& column = out.values[v];
      column.resize(rows.size());
      for (std::size_t i = 0; i < rows.size(); ++i) {
        if (value.other) {
          column[i] = value.other->at(out.t_s[i]);
          continue;
        }
        const OwnValue& own = value.own;
        column[i] = converted_value(*chunk, own.column, rows[i], own.to_si, own.scale, own.offset,
                                    own.column_name, own.unit_name);
        if (!std::isfinite(column[i])) {
          if (!drop_bad_) reject_bad(*chunk, rows[i], own.column_name);
          bad[i] = 1;
        }
      }
    }
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (bad[i]) note_bad(chunk->file, chunk->line_of_row[rows[i]]);
  }
  return true;
}

}  // namespace odocal::detail
