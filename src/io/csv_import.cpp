#include "odocal/io/csv_import.hpp"

#include <fmt/format.h>

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cmath>
#include <deque>
#include <fstream>
#include <iterator>
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
#include "odocal/io/log_block_reader.hpp"
#include "odocal/io/log_directory_output.hpp"
#include "odocal/io/log_reader.hpp"
#include "odocal/io/output_file.hpp"
#include "odocal/io/text_output.hpp"
#include "odocal/io/vehicle_config_io.hpp"
#include "odocal/model/angle.hpp"
#include "staged_clock_shift.hpp"
#include "units.hpp"
#include "vehicle_config_parse.hpp"
#include "yaml_map.hpp"

namespace odocal {
namespace {

using detail::Quantity;
using detail::YamlMap;
namespace fs = std::filesystem;

using detail::SourceFiles;
using detail::StreamChunk;
using detail::StreamReader;

// Writes the complete rows of a stream (every value finite: a value from another file is NaN
// outside that file's span) chunk by chunk. `convert` turns a row's values into the file's
// columns in place (false: leave the row out).
template <typename Convert>
std::size_t write_complete_rows(StreamReader& stream, const fs::path& path,
                                const std::string& header, std::vector<int> decimals,
                                Convert&& convert) {
  StreamCsvWriter out(path, header, std::move(decimals));
  StreamChunk chunk;
  std::vector<double> row;
  while (stream.next(chunk)) {
    for (std::size_t k = 0; k < chunk.rows(); ++k) {
      row.clear();
      for (const std::vector<double>& column : chunk.values) row.push_back(column[k]);
      if (!std::all_of(row.begin(), row.end(), [](double v) { return std::isfinite(v); })) continue;
      if (!convert(chunk.t_s[k], row)) continue;
      out.add(chunk.t_s[k], row.data());
    }
  }
  out.commit();
  return out.rows();
}

// A truth without a heading column: the course over ground of its path (forward driving), from
// the rows 0.5 m of path before and after each. Read forward, each row waits until the path has
// gone 0.5 m beyond it (or the file ends), and the rows more than 0.5 m behind are forgotten.
template <typename Local>
void write_truth_with_course(StreamReader& truth, Local&& local, StreamCsvWriter& out) {
  struct Row {
    double t, x, y, path;
  };
  std::deque<Row> rows;     // from the oldest row a pending one may need, to the newest
  std::size_t pending = 0;  // index in `rows` of the next row to write
  const auto write_next = [&](bool at_end) {
    const Row& row = rows[pending];
    const auto before = std::upper_bound(rows.begin(), rows.end(), row.path - 0.5,
                                         [](double path, const Row& r) { return path < r.path; });
    const Row& a = before == rows.begin() ? rows.front() : *(before - 1);
    const auto after =
        std::lower_bound(rows.begin() + static_cast<std::ptrdiff_t>(pending), rows.end(),
                         row.path + 0.5, [](const Row& r, double path) { return r.path < path; });
    if (after == rows.end() && !at_end) return false;
    const Row& b = after == rows.end() ? rows.back() : *after;
    if (std::hypot(b.x - a.x, b.y - a.y) > 0.5 && std::isfinite(row.x) && std::isfinite(row.y)) {
      const double values[] = {row.x, row.y, std::atan2(b.y - a.y, b.x - a.x)};
      out.add(row.t, values);
    }
    // Rows before `a` are no pending row's `a` any more.
    const auto forget =
        static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, (before - rows.begin()) - 1));
    rows.erase(rows.begin(), rows.begin() + static_cast<std::ptrdiff_t>(forget));
    pending = pending - forget + 1;
    return true;
  };
  StreamChunk chunk;
  std::vector<double> row;
  while (truth.next(chunk)) {
    for (std::size_t k = 0; k < chunk.rows(); ++k) {
      row.clear();
      for (const std::vector<double>& column : chunk.values) row.push_back(column[k]);
      local(row);
      double path = rows.empty() ? 0.0 : rows.back().path;
      if (!rows.empty()) {
        const double step = std::hypot(row[0] - rows.back().x, row[1] - rows.back().y);
        path += std::isfinite(step) ? step : 0.0;
      }
      rows.push_back({chunk.t_s[k], row[0], row[1], path});
      while (pending < rows.size() && write_next(false)) {
      }
    }
  }
  while (pending < rows.size()) write_next(true);
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

// --sync: the doctor's clock-offset estimates against the wheels, applied to the staged files.
std::vector<std::string> sync_clocks(const fs::path& staged) {
  LogBlockReader reader(staged);
  const Diagnosis diagnosis = diagnose_log(reader);
  std::vector<std::string> applied;
  for (const Finding& finding : diagnosis.findings) {
    const char* file = finding.check == "time.gnss_offset"  ? "gnss.csv"
                       : finding.check == "time.imu_offset" ? "imu.csv"
                                                            : nullptr;
    if (!std::isfinite(finding.estimate)) continue;
    if (finding.check == "time.drive_force_offset") {
      detail::advance_column(staged / "wheels.csv", "drive_force_n", finding.estimate);
      applied.push_back(
          fmt::format("wheels.csv drive_force_n: moved by {:+.3f} s onto the "
                      "wheels' clock ({})",
                      -finding.estimate, finding.evidence));
      continue;
    }
    if (file == nullptr) continue;
    detail::shift_times(staged / file, -finding.estimate);
    applied.push_back(fmt::format("{}: clock moved by {:+.3f} s onto the wheels' ({})", file,
                                  -finding.estimate, finding.evidence));
  }
  return applied;
}

std::optional<StreamReader> stream(YamlMap& streams, const std::string& name,
                                   const SourceFiles& files, const YAML::Node& root) {
  auto map = streams.map(name);
  if (!map) return std::nullopt;
  return StreamReader(std::move(*map), root["streams"][name], files);
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
  const SourceFiles files(source_dir, skip_lines);
  constexpr double kPi = std::numbers::pi;
  std::vector<StreamAccount> accounts;

  // Wheels: the unit says what the column holds.
  auto wheels = stream(*streams, "wheels", files, root_node);
  if (!wheels)
    throw InputError({map_file.string(), 0, "streams.wheels"}, "required stream is missing");
  {
    std::vector<std::string> names;
    std::vector<int> decimals;
    std::vector<bool> ticks;
    std::string kind;
    for (const char* wheel : {"rl", "rr", "fl", "fr"}) {
      const bool rear = wheel[0] == 'r';
      if (!rear && !wheels->has(wheel)) continue;
      const Quantity quantity = wheels
                                    ->add_value(wheel, {Quantity::kTicks, Quantity::kAngle,
                                                        Quantity::kAngularSpeed, Quantity::kSpeed})
                                    .second;
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
      names.push_back(fmt::format("{}_{}", wheel, this_kind));
      ticks.push_back(quantity == Quantity::kTicks);
      decimals.push_back(quantity == Quantity::kTicks ? 0 : 9);
    }
    // The tyres' total longitudinal force from the car's bus, for the tyre model's physical terms.
    if (wheels->has("drive_force")) {
      wheels->add_value("drive_force", {Quantity::kForce});
      names.emplace_back("drive_force_n");
      ticks.push_back(false);
      decimals.push_back(1);
    }
    wheels->done();
    // A wrapping counter read with scale -1 runs below zero: back into [0, 2^bits), where the
    // log reader unwraps it.
    const std::optional<double> modulus =
        vehicle.counter_bits ? std::optional(std::ldexp(1.0, *vehicle.counter_bits)) : std::nullopt;
    const std::size_t written =
        write_complete_rows(*wheels, dir / "wheels.csv", fmt::format("t,{}", fmt::join(names, ",")),
                            decimals, [&](double, std::vector<double>& row) {
                              for (std::size_t c = 0; c < row.size(); ++c) {
                                if (!ticks[c] || !modulus) continue;
                                row[c] = std::fmod(row[c], *modulus);
                                if (row[c] < 0.0) row[c] += *modulus;
                              }
                              return true;
                            });
    accounts.push_back(account("wheels", *wheels, written));
  }

  // GNSS: lat/lon (degrees) or local metres; optional altitude, sigma and Doppler speed.
  auto gnss = stream(*streams, "gnss", files, root_node);
  if (!gnss) throw InputError({map_file.string(), 0, "streams.gnss"}, "required stream is missing");
  std::optional<GeographicLib::LocalCartesian> enu;
  {
    const std::string position = gnss->text("position", "latlon");
    if (position != "latlon" && position != "local")
      throw InputError(gnss->map().location("position"), "expected latlon or local");
    const bool latlon = position == "latlon";
    std::vector<std::string> header = {"t", latlon ? "lat" : "x", latlon ? "lon" : "y"};
    gnss->add_value(latlon ? "lat" : "x", {latlon ? Quantity::kAngle : Quantity::kLength});
    gnss->add_value(latlon ? "lon" : "y", {latlon ? Quantity::kAngle : Quantity::kLength});
    std::vector<int> decimals = {latlon ? 9 : 4, latlon ? 9 : 4};
    bool has_alt = false;
    for (const auto& [key, name, quantity] : {std::tuple{"alt", "alt", Quantity::kLength},
                                              std::tuple{"sigma", "sigma_m", Quantity::kLength},
                                              std::tuple{"speed", "speed_mps", Quantity::kSpeed}}) {
      if (!gnss->has(key)) continue;
      gnss->add_value(key, {quantity});
      header.emplace_back(name);
      decimals.push_back(4);
      has_alt = has_alt || std::string_view(key) == "alt";
    }
    gnss->done();
    const std::size_t written =
        write_complete_rows(*gnss, dir / "gnss.csv", fmt::format("{}", fmt::join(header, ",")),
                            decimals, [&](double, std::vector<double>& row) {
                              if (latlon) {
                                row[0] *= 180.0 / kPi;  // back to degrees
                                row[1] *= 180.0 / kPi;
                                // The first complete fix is the local origin of a geodetic truth.
                                if (!enu) enu.emplace(row[0], row[1], has_alt ? row[2] : 0.0);
                              }
                              return true;
                            });
    if (written == 0) throw InputError(gnss->map().location(), "no complete GNSS row");
    accounts.push_back(account("gnss", *gnss, written));
  }

  // IMU: body accelerations and yaw rate, converted to forward-left-up.
  if (auto imu = stream(*streams, "imu", files, root_node)) {
    const std::string frame = imu->text("frame", "flu");
    if (frame != "flu" && frame != "frd")
      throw InputError(imu->map().location("frame"),
                       "expected flu (forward-left-up) or frd (forward-right-down)");
    imu->add_value("ax", {Quantity::kAcceleration});
    imu->add_value("ay", {Quantity::kAcceleration});
    imu->add_value("wz", {Quantity::kAngularSpeed});
    imu->done();
    const std::size_t written = write_complete_rows(
        *imu, dir / "imu.csv", "t,ax,ay,wz", {6, 6, 7}, [&](double, std::vector<double>& row) {
          if (frame == "frd") {  // y right -> left, z down -> up
            row[1] = -row[1];
            row[2] = -row[2];
          }
          return true;
        });
    accounts.push_back(account("imu", *imu, written));
  }

  // Heading: ENU counter-clockwise from east, or compass clockwise from north.
  if (auto heading = stream(*streams, "heading", files, root_node)) {
    const std::string convention = heading->text("convention", "enu_ccw");
    if (convention != "enu_ccw" && convention != "compass_cw") {
      throw InputError(heading->map().location("convention"), "expected enu_ccw or compass_cw");
    }
    heading->add_value("heading", {Quantity::kAngle});
    heading->done();
    const std::size_t written = write_complete_rows(
        *heading, dir / "heading.csv", "t,heading", {7}, [&](double, std::vector<double>& row) {
          row[0] = wrap_angle(convention == "compass_cw" ? kPi / 2 - row[0] : row[0]);
          return true;
        });
    accounts.push_back(account("heading", *heading, written));
  }

  // Truth: in the GNSS's local frame; heading from a column or from the course of the path.
  if (auto truth = stream(*streams, "truth", files, root_node)) {
    const std::string position = truth->text("position", "local");
    if (position != "local" && position != "latlon" && position != "ecef") {
      throw InputError(truth->map().location("position"), "expected local, latlon or ecef");
    }
    if (position != "local" && !enu) {
      throw InputError(
          truth->map().location("position"),
          "a geodetic truth needs the GNSS stream in latlon (its first fix is the local origin)");
    }
    const bool ecef = position == "ecef";
    if (position == "local") {
      truth->add_value("x", {Quantity::kLength});
      truth->add_value("y", {Quantity::kLength});
    } else {
      truth->add_value(ecef ? "x" : "lat", {ecef ? Quantity::kLength : Quantity::kAngle});
      truth->add_value(ecef ? "y" : "lon", {ecef ? Quantity::kLength : Quantity::kAngle});
      truth->add_value(ecef ? "z" : "alt", {Quantity::kLength});
    }
    const std::string heading_source = !truth->has("heading") ? "course"
                                       : truth->is_text("heading")
                                           ? truth->text("heading", "course")
                                           : "column";
    if (heading_source != "course" && heading_source != "column") {
      throw InputError(truth->map().location("heading"),
                       "expected 'course' or a column {column, unit}");
    }
    const std::string convention =
        heading_source == "column" ? truth->text("convention", "enu_ccw") : "enu_ccw";
    if (heading_source == "column") truth->add_value("heading", {Quantity::kAngle});
    truth->done();
    // Each row as x, y (local metres) and its heading (NaN: from the course, filled in later).
    const auto local = [&](std::vector<double>& row) {
      if (position != "local") {
        double lat = row[0] * 180 / kPi, lon = row[1] * 180 / kPi, h = row[2], up = 0, x = 0, y = 0;
        if (ecef) GeographicLib::Geocentric::WGS84().Reverse(row[0], row[1], row[2], lat, lon, h);
        enu->Forward(lat, lon, h, x, y, up);
        const double heading = heading_source == "column" ? row[3] : NAN;
        row = {x, y, heading};
      } else {
        row = {row[0], row[1], heading_source == "column" ? row[2] : NAN};
      }
      if (heading_source == "column")
        row[2] = wrap_angle(convention == "compass_cw" ? kPi / 2 - row[2] : row[2]);
    };
    StreamCsvWriter out(dir / "truth.csv", "t,x,y,heading", {4, 4, 7});
    if (heading_source == "column") {
      StreamChunk chunk;
      std::vector<double> row;
      while (truth->next(chunk)) {
        for (std::size_t k = 0; k < chunk.rows(); ++k) {
          row.clear();
          for (const std::vector<double>& column : chunk.values) row.push_back(column[k]);
          if (!std::all_of(row.begin(), row.end(), [](double v) { return std::isfinite(v); }))
            continue;
          local(row);
          if (std::isfinite(row[0]) && std::isfinite(row[1]) && std::isfinite(row[2]))
            out.add(chunk.t_s[k], row.data());
        }
      }
    } else {
      write_truth_with_course(*truth, local, out);
    }
    out.commit();
    accounts.push_back(account("truth", *truth, out.rows()));
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
