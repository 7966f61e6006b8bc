#include "temp_log_dir.hpp"

#include <unistd.h>

#include <atomic>
#include <fstream>

namespace odocal::testing {
namespace {

// 1 m/s straight east; 96 ticks per revolution of a 2 m wheel: 0.5 rev = 48 ticks per second.
constexpr const char* kVehicle =
    "track_width_m: 1.6\n"
    "circumference_rl_m: 2.0\n"
    "circumference_rr_m: 2.0\n"
    "ticks_per_rev: 96\n";
constexpr const char* kWheels =
    "t,rl_ticks,rr_ticks\n"
    "0.0,0,0\n"
    "1.0,48,48\n"
    "2.0,96,96\n"
    "3.0,144,144\n";
constexpr const char* kGnss =
    "t,x,y\n"
    "0.0,0.0,0.0\n"
    "1.0,1.0,0.0\n"
    "2.0,2.0,0.0\n"
    "3.0,3.0,0.0\n";

}  // namespace

TempLogDir::TempLogDir() {
  static std::atomic<int> counter{0};
  path_ = std::filesystem::temp_directory_path() /
          ("odocal-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
  write("vehicle.yaml", kVehicle);
  write("wheels.csv", kWheels);
  write("gnss.csv", kGnss);
}

TempLogDir::~TempLogDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

void TempLogDir::write(const std::string& name, const std::string& contents) const {
  std::ofstream(path_ / name) << contents;
}

void TempLogDir::remove(const std::string& name) const { std::filesystem::remove(path_ / name); }

}  // namespace odocal::testing
