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

#include "csv_stream_reader.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/log_diagnosis.hpp"
#include "odocal/io/csv_table.hpp"
#include "odocal/io/import_output.hpp"
#include "odocal/io/input_file.hpp"
#include "odocal/io/log_directory_output.hpp"
#include "odocal/io/log_reader.hpp"
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

using detail::StreamReader;
using detail::TableCache;

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

// What one stream left out, for the summary.
struct StreamAccount {
  std::string name;
  std::size_t source_rows{}, written_rows{};
  detail::DroppedRows dropped;
};

StreamAccount account(const std::string& name, const StreamReader& reader, std::size_t written) {
  return {name, reader.source_rows(), written, reader.dropped()};
}

// Notes for what was left out; warnings (the CLI prints them on stderr, exit still 0) when more
// than 1 % of a stream's rows were dropped or a stream covers less than 80 % of the log's span.
void report_accounts(const std::vector<StreamAccount>& accounts, ImportSummary& summary) {
  for (const StreamAccount& a : accounts) {
    if (a.dropped.repeated > 0) {
      summary.notes.push_back(
          fmt::format("{}: {} repeated rows collapsed (dedupe)", a.name, a.dropped.repeated));
    }
    const std::size_t lost = a.source_rows - a.dropped.repeated - a.written_rows;
    if (lost == 0) continue;
    const std::string where =
        a.dropped.first_bad_line > 0
            ? fmt::format(", {} not finite, the first at {}:{}", a.dropped.bad_values,
                          a.dropped.first_bad_file, a.dropped.first_bad_line)
            : "";
    const std::string text =
        fmt::format("{}: {} of {} rows dropped ({:.1f} %{})", a.name, lost, a.source_rows,
                    100.0 * static_cast<double>(lost) / static_cast<double>(a.source_rows), where);
    (static_cast<double>(lost) > 0.01 * static_cast<double>(a.source_rows) ? summary.warnings
                                                                           : summary.notes)
        .push_back(text);
  }
  double first = INFINITY, last = -INFINITY;
  for (const ImportedStreamSummary& s : summary.streams) {
    if (s.name == "truth") continue;
    first = std::min(first, s.start_s);
    last = std::max(last, s.start_s + s.duration_s);
  }
  for (const ImportedStreamSummary& s : summary.streams) {
    if (last > first && s.duration_s < 0.8 * (last - first)) {
      summary.warnings.push_back(fmt::format("{}: covers {:.0f} % of the log's {:.1f} s", s.name,
                                             100.0 * s.duration_s / (last - first), last - first));
    }
  }
}

// Adds `shift_s` to the time (first) column of a log stream file, leaving every other byte.
void shift_times(const fs::path& file, double shift_s) {
  const std::string text = read_input_file(file);
  write_text_file(file, [&](TextBuffer& out) {
    std::size_t at = 0;
    bool header = true;
    while (at < text.size()) {
      const std::size_t end = std::min(text.find('\n', at), text.size());
      const std::string_view line(text.data() + at, end - at);
      at = end + 1;
      if (header || line.empty()) {
        out.print("{}\n", line);
        header = false;
        continue;
      }
      const std::size_t comma = line.find(',');
      const double t = std::stod(std::string(line.substr(0, comma)));
      out.print("{:.6f}{}\n", t + shift_s,
                comma == std::string_view::npos ? std::string_view{} : line.substr(comma));
    }
  });
}

// --sync: the doctor's clock-offset estimates against the wheels, applied to the staged files.
std::vector<std::string> sync_clocks(const fs::path& staged) {
  const Diagnosis diagnosis = diagnose_log(read_log(staged));
  std::vector<std::string> applied;
  for (const Finding& finding : diagnosis.findings) {
    const char* file = finding.check == "time.gnss_offset"  ? "gnss.csv"
                       : finding.check == "time.imu_offset" ? "imu.csv"
                                                            : nullptr;
    if (file == nullptr || !std::isfinite(finding.estimate)) continue;
    shift_times(staged / file, -finding.estimate);
    applied.push_back(fmt::format("{}: clock moved by {:+.3f} s onto the wheels' ({})", file,
                                  -finding.estimate, finding.evidence));
  }
  return applied;
}

std::optional<StreamReader> stream(YamlMap& streams, const std::string& name, TableCache& cache,
                                   const YAML::Node& root) {
  auto map = streams.map(name);
  if (!map) return std::nullopt;
  return StreamReader(std::move(*map), root["streams"][name], cache);
}

}  // namespace

ImportSummary import_csv(const fs::path& map_file, const fs::path& source_dir,
                         const fs::path& out_dir, const CsvImportOptions& options) {
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

  // Per-file reading options: `files: {NAME: {skip_lines: N}}` (lines before the header).
  std::map<std::string, std::size_t> skip_lines;
  if (auto files = root.map("files")) {
    for (const auto& entry : root_node["files"]) {
      const std::string name = entry.first.as<std::string>();
      auto file = files->map(name);
      int skip = 0;
      if (file) {
        file->read("skip_lines", skip, 0, 1'000'000);
        file->reject_unknown_keys();
      }
      skip_lines[name] = static_cast<std::size_t>(skip);
    }
  }
  TableCache cache(source_dir, skip_lines);
  constexpr double kPi = std::numbers::pi;
  std::vector<StreamAccount> accounts;

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
    accounts.push_back(account("wheels", *wheels, rows.size()));
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
    accounts.push_back(account("gnss", *gnss, rows.size()));
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
    accounts.push_back(account("imu", *imu, rows.size()));
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
    accounts.push_back(account("heading", *heading, rows.size()));
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
    accounts.push_back(account("truth", *truth, rows.size()));
  }
  streams->reject_unknown_keys();
  root.reject_unknown_keys();
  write_vehicle_config(vehicle, dir / "vehicle.yaml");

  // Validate the result as any log, and summarise it.
  ImportSummary summary = check_staged_import(dir, out_dir);
  if (options.sync_clocks) {
    const std::vector<std::string> synced = sync_clocks(dir);
    if (!synced.empty()) summary = check_staged_import(dir, out_dir);
    summary.notes.insert(summary.notes.end(), synced.begin(), synced.end());
  }
  output.commit();
  report_accounts(accounts, summary);
  return summary;
}

}  // namespace odocal
