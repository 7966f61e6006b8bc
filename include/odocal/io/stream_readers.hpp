#pragma once
// Converts validated CSV tables into the log's streams (docs/log-format.md). Each function
// throws InputError naming file, line and column for anything the format does not allow.

#include <string>

#include "odocal/data/log.hpp"
#include "odocal/io/csv_table.hpp"

namespace odocal {

struct WheelReadOptions {
  // A wheel moving faster than this is taken as corrupt data (or, for ticks, an unwrapped
  // counter jump) rather than motion.
  double max_wheel_speed_mps = 100.0;
  std::string vehicle_file = "vehicle.yaml";  // named in messages about missing vehicle keys
};

// wheels.csv: t plus {rl,rr,fl,fr}_{ticks,rad,radps,mps}; rl_* and rr_* required.
WheelStream wheel_stream_from_table(const CsvTable& table, const VehicleConfig& vehicle,
                                    const WheelReadOptions& options = {});
// gnss.csv: t,x,y or t,lat,lon; optional alt, sigma_m, speed_mps. Latitude and longitude become
// east and north metres around `origin`, by default the first fix (a file read in chunks passes
// the first chunk's).
GnssStream gnss_stream_from_table(const CsvTable& table, const GeodeticOrigin* origin = nullptr);
// imu.csv: t,ax,ay,wz.
ImuStream imu_stream_from_table(const CsvTable& table);
// heading.csv: t,heading.
HeadingStream heading_stream_from_table(const CsvTable& table);
// truth.csv: t,x,y,heading.
PoseStream pose_stream_from_table(const CsvTable& table);

}  // namespace odocal
