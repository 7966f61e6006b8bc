#include "odocal/io/csv_import.hpp"

#include <fmt/format.h>

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include "odocal/error.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/io/csv_table.hpp"
#include "odocal/io/import_output.hpp"
#include "odocal/io/input_file.hpp"
#include "odocal/io/log_directory_output.hpp"
#include "odocal/io/text_output.hpp"
#include "odocal/io/vehicle_config_io.hpp"
#include "odocal/model/angle.hpp"
#include "units.hpp"
#include "vehicle_config_parse.hpp"
#include "yaml_map.hpp"

namespace odocal {
namespace {

using detail::Quantity;
using detail::YamlMap;
namespace fs = std::filesystem;

// Source tables, read once each.
class TableCache {
 public:
  explicit TableCache(fs::path source_dir) : source_dir_(std::move(source_dir)) {}
  const CsvTable& get(const std::string& file) {
    auto it = tables_.find(file);
    if (it == tables_.end()) it = tables_.emplace(file, read_csv_table(source_dir_ / file)).first;
    return it->second;
  }

 private:
  fs::path source_dir_;
  std::map<std::string, CsvTable> tables_;
};

// One mapped stream: the main file's time base and value columns resampled onto it.
class StreamReader {
 public:
  // `node` is the stream's raw YAML (the map's view of it tracks which keys were read).
  StreamReader(YamlMap map, YAML::Node node, TableCache& cache)
      : node_(std::move(node)), map_(std::move(map)), cache_(cache) {
    map_.read("file", file_);
    if (file_.empty())
      throw InputError(map_.location(), "'file' is required: the CSV that holds this stream");
    auto time = map_.map("time");
    if (!time) throw InputError(map_.location(), "'time' is required: {column, unit, offset_s}");
    std::string column, unit_name = "s";
    double offset_s = 0.0;
    time->read("column", column);
    time->read("unit", unit_name);
    time->read("offset_s", offset_s, -1e12, 1e12);
    time->reject_unknown_keys();
    const auto unit = detail::parse_unit(unit_name);
    if (!unit || unit->quantity != Quantity::kTime) {
      throw InputError(time->location("unit"),
                       "expected a time unit (" + detail::unit_names(Quantity::kTime) + ")");
    }
    const CsvTable& table = cache_.get(file_);
    if (column.empty() || !table.has(column)) {
      throw InputError(time->location("column"),
                       fmt::format("column '{}' is not in {}", column, table.file));
    }
    t_s_ = table.column(column);
    for (std::size_t k = 0; k < t_s_.size(); ++k) {
      t_s_[k] = t_s_[k] * unit->to_si + offset_s;
      if (!std::isfinite(t_s_[k]))
        throw InputError(table.at(k, column), "not a finite time after the unit conversion");
      if (k > 0 && !(t_s_[k] > t_s_[k - 1])) {
        throw InputError(table.at(k, column), "time must strictly increase");
      }
    }
  }

  bool has(const std::string& key) const { return map_.has(key); }
  bool is_text(const std::string& key) const { return node_[key].IsScalar(); }
  YamlMap& map() { return map_; }
  const std::vector<double>& t_s() const { return t_s_; }

  std::string text(const std::string& key, const std::string& fallback) {
    std::string value = fallback;
    map_.read(key, value);
    return value;
  }

  // A value column in SI units on the stream's time base; `quantities` are the accepted kinds.
  std::pair<std::vector<double>, Quantity> values(const std::string& key,
                                                  std::initializer_list<Quantity> quantities) {
    auto spec = map_.map(key);
    if (!spec) throw InputError(map_.location(), fmt::format("'{}' is required", key));
    std::string file = file_, column, unit_name;
    double scale = 1.0;  // -1: a column whose sign is reversed (an encoder counting backwards)
    spec->read("file", file);
    spec->read("column", column);
    spec->read("unit", unit_name);
    spec->read("scale", scale, -1e6, 1e6);
    if (scale == 0.0) throw InputError(spec->location("scale"), "must not be 0");
    spec->reject_unknown_keys();
    const auto unit = detail::parse_unit(unit_name);
    if (!unit ||
        std::find(quantities.begin(), quantities.end(), unit->quantity) == quantities.end()) {
      std::string accepted;
      for (Quantity q : quantities)
        accepted += (accepted.empty() ? "" : ", ") + detail::unit_names(q);
      throw InputError(spec->location("unit"), fmt::format("expected one of {}", accepted));
    }
    const CsvTable& table = cache_.get(file);
    if (column.empty() || !table.has(column)) {
      throw InputError(spec->location("column"),
                       fmt::format("column '{}' is not in {}", column, table.file));
    }
    std::vector<double> out = table.column(column);
    for (std::size_t k = 0; k < out.size(); ++k) {
      // An empty cell (NaN) is a missing value; a finite one that overflows is an error.
      const double converted = out[k] * unit->to_si * scale;
      if (std::isfinite(out[k]) && !std::isfinite(converted)) {
        throw InputError(
            table.at(k, column),
            fmt::format("{:g} {} is not a finite value in SI units", out[k], unit_name));
      }
      out[k] = converted;
    }
    if (file == file_) return {std::move(out), unit->quantity};
    // Another file of the same sensor: interpolate onto this stream's time base via its own
    // time column, which must have the same name and unit (the stream's `time` applies).
    YAML::Node other;
    other["file"] = file;
    other["time"] = node_["time"];
    StreamReader other_time(YamlMap(other, map_.file(), map_.key_path("time")), other, cache_);
    std::vector<double> resampled(t_s_.size(), NAN);
    for (std::size_t k = 0; k < t_s_.size(); ++k) {
      if (const auto v = interpolate_linear(other_time.t_s(), out, t_s_[k])) resampled[k] = *v;
    }
    return {std::move(resampled), unit->quantity};
  }

  void done() { map_.reject_unknown_keys(); }

 private:
  YAML::Node node_;
  YamlMap map_;
  TableCache& cache_;
  std::string file_;
  std::vector<double> t_s_;
};

// Rows where every column is finite (resampled columns are NaN outside their file's span).
std::vector<std::size_t> complete_rows(const std::vector<const std::vector<double>*>& columns,
                                       std::size_t rows) {
  std::vector<std::size_t> keep;
  for (std::size_t k = 0; k < rows; ++k) {
    bool ok = true;
    for (const auto* column : columns) ok = ok && std::isfinite((*column)[k]);
    if (ok) keep.push_back(k);
  }
  return keep;
}

std::optional<StreamReader> stream(YamlMap& streams, const std::string& name, TableCache& cache,
                                   const YAML::Node& root) {
  auto map = streams.map(name);
  if (!map) return std::nullopt;
  return StreamReader(std::move(*map), root["streams"][name], cache);
}

}  // namespace

ImportSummary import_csv(const fs::path& map_file, const fs::path& source_dir,
                         const fs::path& out_dir) {
  const YAML::Node root_node = detail::parse_yaml(read_input_file(map_file), map_file.string());
  YamlMap root(root_node, map_file.string(), "");
  auto vehicle_map = root.map("vehicle");
  if (!vehicle_map)
    throw InputError({map_file.string(), 0, "vehicle"}, "required section is missing");
  const VehicleConfig vehicle = detail::parse_vehicle_config(*vehicle_map);
  auto streams = root.map("streams");
  if (!streams) throw InputError({map_file.string(), 0, "streams"}, "required section is missing");
  refuse_overlapping_directories(source_dir, out_dir);
  LogDirectoryOutput output(out_dir);
  const fs::path& dir = output.staging();

  TableCache cache(source_dir);
  constexpr double kPi = std::numbers::pi;

  // Wheels: the unit says what the column holds.
  auto wheels = stream(*streams, "wheels", cache, root_node);
  if (!wheels)
    throw InputError({map_file.string(), 0, "streams.wheels"}, "required stream is missing");
  {
    std::vector<std::string> names;
    std::vector<std::vector<double>> values;
    std::string kind;
    for (const char* wheel : {"rl", "rr", "fl", "fr"}) {
      const bool rear = wheel[0] == 'r';
      if (!rear && !wheels->has(wheel)) continue;
      auto [column, quantity] = wheels->values(
          wheel, {Quantity::kTicks, Quantity::kAngle, Quantity::kAngularSpeed, Quantity::kSpeed});
      const std::string this_kind =
          enum_name(quantity == Quantity::kTicks          ? WheelUnit::kTicks
                    : quantity == Quantity::kAngle        ? WheelUnit::kRadians
                    : quantity == Quantity::kAngularSpeed ? WheelUnit::kRadiansPerSecond
                                                          : WheelUnit::kMetresPerSecond);
      if (rear && !kind.empty() && kind != this_kind) {
        throw InputError(wheels->map().location(wheel),
                         "rl and rr must be the same kind of value (both ticks, angles, angular "
                         "speeds or speeds)");
      }
      kind = rear ? this_kind : kind;
      if (quantity == Quantity::kTicks && vehicle.counter_bits) {
        // A wrapping counter read with scale -1 runs below zero: back into [0, 2^bits), where
        // the log reader unwraps it.
        const double modulus = std::ldexp(1.0, *vehicle.counter_bits);
        for (double& v : column) {
          if (!std::isfinite(v)) continue;
          v = std::fmod(v, modulus);
          if (v < 0.0) v += modulus;
        }
      }
      names.push_back(fmt::format("{}_{}", wheel, this_kind));
      values.push_back(std::move(column));
    }
    wheels->done();
    std::vector<const std::vector<double>*> columns;
    for (const auto& v : values) columns.push_back(&v);
    const auto rows = complete_rows(columns, wheels->t_s().size());
    std::vector<int> decimals(columns.size(), 9);
    for (std::size_t c = 0; c < names.size(); ++c) {
      if (names[c].ends_with("_ticks")) decimals[c] = 0;
    }
    write_stream_csv(dir / "wheels.csv", fmt::format("t,{}", fmt::join(names, ",")), wheels->t_s(),
                     columns, rows, decimals);
  }

  // GNSS: lat/lon (degrees) or local metres; optional altitude, sigma and Doppler speed.
  auto gnss = stream(*streams, "gnss", cache, root_node);
  if (!gnss) throw InputError({map_file.string(), 0, "streams.gnss"}, "required stream is missing");
  std::optional<GeographicLib::LocalCartesian> enu;
  {
    const std::string position = gnss->text("position", "latlon");
    if (position != "latlon" && position != "local")
      throw InputError(gnss->map().location("position"), "expected latlon or local");
    const bool latlon = position == "latlon";
    std::vector<std::string> header = {"t", latlon ? "lat" : "x", latlon ? "lon" : "y"};
    std::vector<std::vector<double>> values;
    values.push_back(
        gnss->values(latlon ? "lat" : "x", {latlon ? Quantity::kAngle : Quantity::kLength}).first);
    values.push_back(
        gnss->values(latlon ? "lon" : "y", {latlon ? Quantity::kAngle : Quantity::kLength}).first);
    if (latlon) {
      for (auto& column : values)
        for (double& v : column) v *= 180.0 / kPi;  // back to degrees
    }
    std::vector<int> decimals = {latlon ? 9 : 4, latlon ? 9 : 4};
    for (const auto& [key, name, quantity] : {std::tuple{"alt", "alt", Quantity::kLength},
                                              std::tuple{"sigma", "sigma_m", Quantity::kLength},
                                              std::tuple{"speed", "speed_mps", Quantity::kSpeed}}) {
      if (!gnss->has(key)) continue;
      values.push_back(gnss->values(key, {quantity}).first);
      header.emplace_back(name);
      decimals.push_back(4);
    }
    gnss->done();
    std::vector<const std::vector<double>*> columns;
    for (const auto& v : values) columns.push_back(&v);
    const auto rows = complete_rows(columns, gnss->t_s().size());
    if (rows.empty()) throw InputError(gnss->map().location(), "no complete GNSS row");
    if (latlon) {
      const bool has_alt = std::find(header.begin(), header.end(), "alt") != header.end();
      enu.emplace(values[0][rows[0]], values[1][rows[0]], has_alt ? values[2][rows[0]] : 0.0);
    }
    write_stream_csv(dir / "gnss.csv", fmt::format("{}", fmt::join(header, ",")), gnss->t_s(),
                     columns, rows, decimals);
  }

  // IMU: body accelerations and yaw rate, converted to forward-left-up.
  if (auto imu = stream(*streams, "imu", cache, root_node)) {
    const std::string frame = imu->text("frame", "flu");
    if (frame != "flu" && frame != "frd")
      throw InputError(imu->map().location("frame"),
                       "expected flu (forward-left-up) or frd (forward-right-down)");
    auto ax = imu->values("ax", {Quantity::kAcceleration}).first;
    auto ay = imu->values("ay", {Quantity::kAcceleration}).first;
    auto wz = imu->values("wz", {Quantity::kAngularSpeed}).first;
    imu->done();
    if (frame == "frd") {  // y right -> left, z down -> up
      for (double& v : ay) v = -v;
      for (double& v : wz) v = -v;
    }
    const auto rows = complete_rows({&ax, &ay, &wz}, imu->t_s().size());
    write_stream_csv(dir / "imu.csv", "t,ax,ay,wz", imu->t_s(), {&ax, &ay, &wz}, rows, {6, 6, 7});
  }

  // Heading: ENU counter-clockwise from east, or compass clockwise from north.
  if (auto heading = stream(*streams, "heading", cache, root_node)) {
    const std::string convention = heading->text("convention", "enu_ccw");
    if (convention != "enu_ccw" && convention != "compass_cw") {
      throw InputError(heading->map().location("convention"), "expected enu_ccw or compass_cw");
    }
    auto values = heading->values("heading", {Quantity::kAngle}).first;
    heading->done();
    for (double& v : values) v = wrap_angle(convention == "compass_cw" ? kPi / 2 - v : v);
    const auto rows = complete_rows({&values}, heading->t_s().size());
    write_stream_csv(dir / "heading.csv", "t,heading", heading->t_s(), {&values}, rows, {7});
  }

  // Truth: in the GNSS's local frame; heading from a column or from the course of the path.
  if (auto truth = stream(*streams, "truth", cache, root_node)) {
    const std::string position = truth->text("position", "local");
    if (position != "local" && position != "latlon" && position != "ecef") {
      throw InputError(truth->map().location("position"), "expected local, latlon or ecef");
    }
    if (position != "local" && !enu) {
      throw InputError(
          truth->map().location("position"),
          "a geodetic truth needs the GNSS stream in latlon (its first fix is the local origin)");
    }
    std::vector<double> x, y;
    if (position == "local") {
      x = truth->values("x", {Quantity::kLength}).first;
      y = truth->values("y", {Quantity::kLength}).first;
    } else {
      const bool ecef = position == "ecef";
      auto a =
          truth->values(ecef ? "x" : "lat", {ecef ? Quantity::kLength : Quantity::kAngle}).first;
      auto b =
          truth->values(ecef ? "y" : "lon", {ecef ? Quantity::kLength : Quantity::kAngle}).first;
      auto c = truth->values(ecef ? "z" : "alt", {Quantity::kLength}).first;
      x.resize(a.size());
      y.resize(a.size());
      for (std::size_t k = 0; k < a.size(); ++k) {
        double lat = a[k] * 180 / kPi, lon = b[k] * 180 / kPi, h = c[k], up = 0;
        if (ecef) GeographicLib::Geocentric::WGS84().Reverse(a[k], b[k], c[k], lat, lon, h);
        enu->Forward(lat, lon, h, x[k], y[k], up);
      }
    }
    std::vector<double> yaw(x.size(), NAN);
    const std::string heading_source = !truth->has("heading") ? "course"
                                       : truth->is_text("heading")
                                           ? truth->text("heading", "course")
                                           : "column";
    if (heading_source == "course") {
      // Course over ground of the truth path (forward driving), from the neighbours 0.5 m of
      // path before and after; found by bisection over the path length (a standing stretch of
      // n rows would otherwise cost n^2).
      std::vector<double> path_m(x.size(), 0.0);
      for (std::size_t k = 1; k < x.size(); ++k) {
        const double step = std::hypot(x[k] - x[k - 1], y[k] - y[k - 1]);
        path_m[k] = path_m[k - 1] + (std::isfinite(step) ? step : 0.0);
      }
      for (std::size_t k = 0; k < x.size(); ++k) {
        const auto first_before =
            std::upper_bound(path_m.begin(), path_m.end(), path_m[k] - 0.5) - path_m.begin();
        const std::size_t a = first_before > 0 ? static_cast<std::size_t>(first_before) - 1 : 0;
        const std::size_t b = std::min<std::size_t>(
            static_cast<std::size_t>(
                std::lower_bound(path_m.begin(), path_m.end(), path_m[k] + 0.5) - path_m.begin()),
            x.size() - 1);
        if (std::hypot(x[b] - x[a], y[b] - y[a]) > 0.5)
          yaw[k] = std::atan2(y[b] - y[a], x[b] - x[a]);
      }
    } else if (heading_source == "column") {
      const std::string convention = truth->text("convention", "enu_ccw");
      yaw = truth->values("heading", {Quantity::kAngle}).first;
      for (double& v : yaw) v = wrap_angle(convention == "compass_cw" ? kPi / 2 - v : v);
    } else {
      throw InputError(truth->map().location("heading"),
                       "expected 'course' or a column {column, unit}");
    }
    truth->done();
    const auto rows = complete_rows({&x, &y, &yaw}, truth->t_s().size());
    write_stream_csv(dir / "truth.csv", "t,x,y,heading", truth->t_s(), {&x, &y, &yaw}, rows,
                     {4, 4, 7});
  }
  streams->reject_unknown_keys();
  root.reject_unknown_keys();
  write_vehicle_config(vehicle, dir / "vehicle.yaml");

  // Validate the result as any log, and summarise it.
  ImportSummary summary = check_staged_import(dir, out_dir);
  output.commit();
  return summary;
}

}  // namespace odocal
