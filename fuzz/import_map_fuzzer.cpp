// `odocal import csv`: the input is a column map applied to a fixed small logger directory (two
// wheels in ticks and a millisecond clock, GNSS in lat/lon with altitude, an IMU in FRD, a
// compass heading). An import ends in a log that reads back, or in an odocal::Error with nothing
// written.

#include <filesystem>

#include "fuzz_support.hpp"
#include "odocal/io/csv_import.hpp"

namespace {

using namespace odocal;
namespace fs = std::filesystem;

const fs::path& logger_directory() {
  static const fs::path directory = [] {
    const fs::path dir = fuzz::scratch_directory() / "logger";
    fs::create_directories(dir);
    std::string wheels = "time_ms,left,right,speed_kmh\n";
    std::string gnss = "time_ms,lat,lon,alt,hdg_deg\n";
    std::string imu = "time_ms,ax,ay,gz\n";
    for (int k = 0; k < 60; ++k) {
      wheels += std::to_string(k * 100) + "," + std::to_string(5 * k) + "," +
                std::to_string(5 * k + k / 10) + ",36\n";
      gnss += std::to_string(k * 100) + ",49.0," + std::to_string(8.0 + 1.3e-5 * k) + ",100,90\n";
      imu += std::to_string(k * 100) + ",0.1,0.0,0.001\n";
    }
    fuzz::write_file(dir / "wheels.csv", wheels);
    fuzz::write_file(dir / "gnss.csv", gnss);
    fuzz::write_file(dir / "imu.csv", imu);
    return dir;
  }();
  return directory;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const fs::path map = fuzz::scratch_directory() / "map.yaml";
  const fs::path out = fuzz::scratch_directory() / "log";
  fuzz::write_file(map, fuzz::as_text(data, size));
  fuzz::expect_only_odocal_errors([&] {
    const ImportSummary summary = import_csv(map, logger_directory(), out);
    fuzz::require(!summary.streams.empty());
  });
  return 0;
}
