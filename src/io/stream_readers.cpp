#include "odocal/io/stream_readers.hpp"

#include <GeographicLib/LocalCartesian.hpp>

#include "odocal/data/physical_limits.hpp"
#include "odocal/model/angle.hpp"
#include "table_checks.hpp"

namespace odocal {
namespace {

using detail::require_within;

void require_rows_and_time(const CsvTable& table) {
  detail::require_increasing_time(table);
  detail::require_rows(table, 1, "need at least 1");
}

}  // namespace

GnssStream gnss_stream_from_table(const CsvTable& table, const GeodeticOrigin* origin) {
  detail::require_known_columns(table,
                                {"t", "x", "y", "lat", "lon", "alt", "sigma_m", "speed_mps"});
  const bool metric = table.has("x") || table.has("y");
  const bool geodetic = table.has("lat") || table.has("lon");
  if (metric == geodetic) {
    throw InputError({table.file, 1, ""},
                     metric
                         ? "give positions either as x,y or as lat,lon, not both"
                         : "missing position columns: expected x,y (metres) or lat,lon (degrees)");
  }
  require_rows_and_time(table);

  GnssStream stream;
  stream.t_s = table.column("t");
  if (table.has("alt")) {
    require_within(table, "alt", kAltitudeM, "an altitude in metres");
    stream.altitude_m = table.column("alt");
  }
  if (table.has("sigma_m")) {
    detail::require_range(table, "sigma_m", 1e-6, 1e6, "a positive 1-sigma in metres");
    stream.sigma_m = table.column("sigma_m");
  }
  if (table.has("speed_mps")) {
    detail::require_range(table, "speed_mps", 0.0, 1e3, "a speed over ground from 0 to 1000 m/s");
    stream.speed_mps = table.column("speed_mps");
  }
  if (metric) {
    require_within(table, "x", kPositionM, "a local position in metres");
    require_within(table, "y", kPositionM, "a local position in metres");
    stream.x_m = table.column("x");
    stream.y_m = table.column("y");
    return stream;
  }

  detail::require_range(table, "lat", -90.0, 90.0, "latitude in degrees from -90 to 90");
  detail::require_range(table, "lon", -180.0, 180.0, "longitude in degrees from -180 to 180");
  const std::vector<double>& lat = table.column("lat");
  const std::vector<double>& lon = table.column("lon");
  const auto altitude = [&](std::size_t k) {
    return stream.altitude_m.empty() ? 0.0 : stream.altitude_m[k];
  };
  stream.origin = origin != nullptr ? *origin : GeodeticOrigin{lat[0], lon[0], altitude(0)};
  const GeographicLib::LocalCartesian enu(stream.origin->latitude_deg, stream.origin->longitude_deg,
                                          stream.origin->altitude_m);
  stream.x_m.resize(table.rows());
  stream.y_m.resize(table.rows());
  for (std::size_t k = 0; k < table.rows(); ++k) {
    double up_m = 0.0;
    enu.Forward(lat[k], lon[k], altitude(k), stream.x_m[k], stream.y_m[k], up_m);
  }
  return stream;
}

ImuStream imu_stream_from_table(const CsvTable& table) {
  detail::require_known_columns(table, {"t", "ax", "ay", "wz"});
  require_rows_and_time(table);
  require_within(table, "ax", kAccelerationMps2, "an acceleration in m/s^2");
  require_within(table, "ay", kAccelerationMps2, "an acceleration in m/s^2");
  require_within(table, "wz", kRateRadps, "a yaw rate in rad/s");
  return {table.column("t"), table.column("ax"), table.column("ay"), table.column("wz")};
}

HeadingStream heading_stream_from_table(const CsvTable& table) {
  detail::require_known_columns(table, {"t", "heading"});
  require_rows_and_time(table);
  require_within(table, "heading", kHeadingRad, "a heading in radians");
  HeadingStream stream{table.column("t"), table.column("heading")};
  for (double& heading : stream.heading_rad) heading = wrap_angle(heading);
  return stream;
}

PoseStream pose_stream_from_table(const CsvTable& table) {
  detail::require_known_columns(table, {"t", "x", "y", "heading"});
  require_rows_and_time(table);
  require_within(table, "x", kPositionM, "a local position in metres");
  require_within(table, "y", kPositionM, "a local position in metres");
  require_within(table, "heading", kHeadingRad, "a heading in radians");
  const std::vector<double>& x = table.column("x");
  const std::vector<double>& y = table.column("y");
  const std::vector<double>& heading = table.column("heading");
  PoseStream stream;
  stream.t_s = table.column("t");
  stream.pose.reserve(table.rows());
  for (std::size_t k = 0; k < table.rows(); ++k) stream.pose.emplace_back(x[k], y[k], heading[k]);
  return stream;
}

}  // namespace odocal
