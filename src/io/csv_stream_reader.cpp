#include "csv_stream_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "odocal/error.hpp"
#include "odocal/estimation/interpolation.hpp"

namespace odocal::detail {

const CsvTable& TableCache::get(const std::string& file) {
  auto it = tables_.find(file);
  if (it == tables_.end()) {
    CsvOptions options;
    options.logger_dialect = true;
    options.bad_numbers_as_nan = true;  // garbage in a column nobody uses must not matter
    if (const auto skip = skip_lines_.find(file); skip != skip_lines_.end())
      options.skip_lines = skip->second;
    it = tables_.emplace(file, read_csv_table(source_dir_ / file, options)).first;
  }
  return it->second;
}

StreamReader::TimeSpec StreamReader::read_time_spec(YamlMap& time) const {
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

std::vector<double> StreamReader::times_of(const CsvTable& table, const TimeSpec& spec) const {
  if (spec.column.empty() || !table.has(spec.column)) {
    throw InputError(spec.where, fmt::format("column '{}' is not in {}", spec.column, table.file));
  }
  std::vector<double> t = table.column(spec.column);
  double last = -INFINITY;
  std::size_t last_row = 0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    t[k] = t[k] * spec.to_si + spec.offset_s;
    if (!std::isfinite(t[k])) {
      if (!drop_bad_) {
        throw InputError(table.at(k, spec.column),
                         "not a finite time after the unit conversion (bad_values: drop leaves "
                         "such rows out)");
      }
      t[k] = NAN;
      continue;
    }
    if (!(t[k] > last) && last > -INFINITY) {
      throw InputError(table.at(k, spec.column),
                       fmt::format("time must strictly increase (line {} has {:.9g} s)",
                                   table.line_of_row[last_row], last));
    }
    last = t[k];
    last_row = k;
  }
  return t;
}

void StreamReader::note_bad_time(const CsvTable& table, std::size_t row) {
  ++dropped_.bad_values;
  if (dropped_.first_bad_line == 0 || table.line_of_row[row] < dropped_.first_bad_line) {
    dropped_.first_bad_line = table.line_of_row[row];
    dropped_.first_bad_file = table.file;
  }
}

StreamReader::StreamReader(YamlMap map, YAML::Node node, TableCache& cache)
    : node_(std::move(node)), map_(std::move(map)), cache_(cache) {
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
  const CsvTable& table = cache_.get(file_);
  source_rows_ = table.rows();
  const std::vector<double> t = times_of(table, time_);

  // dedupe: a row whose named columns all equal those of the row kept before it repeats it.
  std::vector<const std::vector<double>*> dedupe;
  for (const YAML::Node& name : map_.sequence("dedupe")) {
    const std::string column = name.IsScalar() ? name.Scalar() : "";
    if (!table.has(column)) {
      throw InputError(map_.location("dedupe"),
                       fmt::format("column '{}' is not in {}", column, table.file));
    }
    dedupe.push_back(&table.column(column));
  }
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (std::isnan(t[k])) {
      note_bad_time(table, k);
      continue;
    }
    if (!dedupe.empty() && !rows_.empty() &&
        std::all_of(dedupe.begin(), dedupe.end(),
                    [&](const auto* column) { return (*column)[k] == (*column)[rows_.back()]; })) {
      ++dropped_.repeated;
      continue;
    }
    rows_.push_back(k);
    t_s_.push_back(t[k]);
  }
  value_bad_.assign(rows_.size(), 0);
}

DroppedRows StreamReader::dropped() const {
  DroppedRows out = dropped_;
  for (std::size_t i = 0; i < value_bad_.size(); ++i) {
    if (!value_bad_[i]) continue;
    ++out.bad_values;
    const std::size_t line = cache_.get(file_).line_of_row[rows_[i]];
    if (out.first_bad_line == 0 || line < out.first_bad_line) {
      out.first_bad_line = line;
      out.first_bad_file = cache_.get(file_).file;
    }
  }
  return out;
}

std::string StreamReader::text(const std::string& key, const std::string& fallback) {
  std::string value = fallback;
  map_.read(key, value);
  return value;
}

std::pair<std::vector<double>, Quantity> StreamReader::values(
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
  const CsvTable& table = cache_.get(file);
  if (column.empty() || !table.has(column)) {
    throw InputError(spec->location("column"),
                     fmt::format("column '{}' is not in {}", column, table.file));
  }
  const std::vector<double>& raw = table.column(column);
  const auto convert = [&](std::size_t row) {
    const double converted = raw[row] * unit->to_si * scale + offset;
    if (std::isfinite(raw[row]) && !std::isfinite(converted)) {
      throw InputError(
          table.at(row, column),
          fmt::format("{:g} {} is not a finite value in SI units", raw[row], unit_name));
    }
    return converted;
  };
  const auto bad = [&](std::size_t row) {
    if (!drop_bad_) {
      throw InputError(table.at(row, column),
                       "expected a finite number (bad_values: drop leaves such rows out)");
    }
  };
  if (file == file_) {
    std::vector<double> out(rows_.size());
    for (std::size_t i = 0; i < rows_.size(); ++i) {
      out[i] = convert(rows_[i]);
      if (!std::isfinite(out[i])) {
        bad(rows_[i]);
        value_bad_[i] = 1;
      }
    }
    return {std::move(out), unit->quantity};
  }
  // Another file of the same sensor: its finite samples on its own clock, interpolated onto this
  // stream's time base (NaN outside its span).
  const std::vector<double> t = times_of(table, other_time);
  std::vector<double> other_t, other_v;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double v = convert(k);
    if (std::isnan(t[k]) || !std::isfinite(v)) {
      if (!std::isnan(t[k])) bad(k);
      continue;
    }
    other_t.push_back(t[k]);
    other_v.push_back(v);
  }
  std::vector<double> resampled(t_s_.size(), NAN);
  for (std::size_t k = 0; k < t_s_.size(); ++k) {
    if (const auto v = interpolate_linear(other_t, other_v, t_s_[k])) resampled[k] = *v;
  }
  return {std::move(resampled), unit->quantity};
}

}  // namespace odocal::detail
