#include "odocal/io/log_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <system_error>

#include "odocal/io/csv_table.hpp"
#include "odocal/io/input_file.hpp"
#include "odocal/io/vehicle_config_io.hpp"

namespace odocal {
namespace {

// A stream that has no sample inside the wheel time span is a clock mismatch, not data.
void require_overlap(const std::vector<double>& t_s, const WheelStream& wheels,
                     const std::string& file) {
  const double begin = wheels.t_s.front();
  const double end = wheels.t_s.back();
  const auto inside = [&](double t) { return t >= begin && t <= end; };
  if (std::none_of(t_s.begin(), t_s.end(), inside)) {
    throw InputError({file, 0, "t"},
                     fmt::format("no sample inside the wheel time span [{}, {}] s: streams must "
                                 "share one clock",
                                 begin, end));
  }
}

}  // namespace

Log read_log(const std::filesystem::path& directory, const LogReadOptions& options) {
  std::error_code error;
  const auto status = std::filesystem::status(directory, error);
  if (error && error != std::errc::no_such_file_or_directory)
    throw InputError({directory.string(), 0, ""}, "cannot open: " + error.message());
  if (!std::filesystem::is_directory(status)) {
    throw InputError({directory.string(), 0, ""}, std::filesystem::exists(status)
                                                      ? "not a directory: a log is a directory"
                                                      : "log directory does not exist");
  }
  Log log;
  log.source = directory.string();
  const std::filesystem::path vehicle_file = directory / "vehicle.yaml";
  log.vehicle = read_vehicle_config(vehicle_file);

  WheelReadOptions wheel_options = options.wheels;
  wheel_options.vehicle_file = vehicle_file.string();
  log.wheels =
      wheel_stream_from_table(read_csv_table(directory / "wheels.csv"), log.vehicle, wheel_options);

  const std::filesystem::path gnss_file = directory / "gnss.csv";
  log.gnss = gnss_stream_from_table(read_csv_table(gnss_file));
  require_overlap(log.gnss.t_s, log.wheels, gnss_file.string());

  const auto optional_file = [&](const char* name) -> std::optional<std::filesystem::path> {
    const std::filesystem::path path = directory / name;
    if (input_exists(path)) return path;
    return std::nullopt;
  };
  if (const auto path = optional_file("imu.csv")) {
    log.imu = imu_stream_from_table(read_csv_table(*path));
    require_overlap(log.imu->t_s, log.wheels, path->string());
  }
  if (const auto path = optional_file("heading.csv")) {
    log.heading = heading_stream_from_table(read_csv_table(*path));
    require_overlap(log.heading->t_s, log.wheels, path->string());
  }
  if (options.read_truth) {
    if (const auto path = optional_file("truth.csv")) {
      log.truth = pose_stream_from_table(read_csv_table(*path));
      require_overlap(log.truth->t_s, log.wheels, path->string());
    }
  }
  return log;
}

}  // namespace odocal
