#include "doctor_faults.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "run_cli.hpp"

namespace odocal::testing {

namespace fs = std::filesystem;
namespace {
constexpr double kPi = std::numbers::pi;
}  // namespace

// Rewrites a CSV file row by row (every column as a number).
void edit_csv(const fs::path& file, const std::function<void(Row&)>& edit,
              std::vector<std::string> header) {
  std::istringstream in(read_text_file(file.string()));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::stringstream cells(line); std::getline(cells, line, ',');) names.push_back(line);
  if (header.empty()) header = names;
  std::string out = fmt::format("{}\n", fmt::join(header, ","));
  while (std::getline(in, line)) {
    Row row;
    std::stringstream cells(line);
    for (const std::string& name : names) {
      std::string cell;
      std::getline(cells, cell, ',');
      row[name] = std::stod(cell);
    }
    edit(row);
    std::vector<std::string> values;
    for (const std::string& name : header) values.push_back(fmt::format("{:.10g}", row[name]));
    out += fmt::format("{}\n", fmt::join(values, ","));
  }
  std::ofstream(file) << out;
}

namespace {

// Multiplies one number in the log's vehicle.yaml.
void scale_vehicle_value(const fs::path& log, const std::string& key, double factor) {
  std::string yaml = read_text_file((log / "vehicle.yaml").string());
  const auto at = yaml.find(key + ": ") + key.size() + 2;
  const auto end = yaml.find('\n', at);
  yaml.replace(at, end - at, fmt::format("{:.6f}", factor * std::stod(yaml.substr(at, end - at))));
  std::ofstream(log / "vehicle.yaml") << yaml;
}

double wrap16(double ticks) { return std::fmod(std::fmod(ticks, 65536.0) + 65536.0, 65536.0); }

}  // namespace

std::vector<Fault> faults() {
  const auto shift = [](const char* file, double by) {
    return [=](const fs::path& log) { edit_csv(log / file, [&](Row& r) { r["t"] += by; }); };
  };
  return {
      {"left/right swapped", "",
       [](const fs::path& log) {
         edit_csv(log / "wheels.csv", [](Row& r) { std::swap(r["rl_ticks"], r["rr_ticks"]); });
       },
       "wheels.swapped"},
      {"RL sign", "",
       [](const fs::path& log) {
         edit_csv(log / "wheels.csv", [](Row& r) { r["rl_ticks"] = wrap16(-r["rl_ticks"]); });
       },
       "wheels.rl_sign"},
      {"RR sign", "",
       [](const fs::path& log) {
         edit_csv(log / "wheels.csv", [](Row& r) { r["rr_ticks"] = wrap16(-r["rr_ticks"]); });
       },
       "wheels.rr_sign"},
      {"both signs", "",
       [](const fs::path& log) {
         edit_csv(log / "wheels.csv", [](Row& r) {
           r["rl_ticks"] = wrap16(-r["rl_ticks"]);
           r["rr_ticks"] = wrap16(-r["rr_ticks"]);
         });
       },
       "wheels.sign"},
      {"ticks_per_rev x2", "",
       [](const fs::path& log) {
         std::string yaml = read_text_file((log / "vehicle.yaml").string());
         yaml.replace(yaml.find("ticks_per_rev: 96"), 17, "ticks_per_rev: 192");
         std::ofstream(log / "vehicle.yaml") << yaml;
       },
       "wheels.rl_unit"},
      {"diameter for circumference", "",
       [](const fs::path& log) {
         scale_vehicle_value(log, "circumference_rl_m", 1 / kPi);
         scale_vehicle_value(log, "circumference_rr_m", 1 / kPi);
       },
       "wheels.rl_unit"},
      {"circumference 15 % off", "",
       [](const fs::path& log) { scale_vehicle_value(log, "circumference_rr_m", 1.15); },
       "vehicle.rr_circumference"},
      {"rpm as rad/s", "--wheel-output radps",
       [](const fs::path& log) {
         edit_csv(log / "wheels.csv", [](Row& r) {
           r["rl_radps"] *= 60 / (2 * kPi);
           r["rr_radps"] *= 60 / (2 * kPi);
         });
       },
       "wheels.rl_unit"},
      {"km/h as m/s", "--wheel-output mps",
       [](const fs::path& log) {
         edit_csv(log / "wheels.csv", [](Row& r) {
           r["rl_mps"] *= 3.6;
           r["rr_mps"] *= 3.6;
         });
       },
       "wheels.rl_unit"},
      {"deg as rad", "--wheel-output rad",
       [](const fs::path& log) {
         edit_csv(log / "wheels.csv", [](Row& r) {
           r["rl_rad"] *= 180 / kPi;
           r["rr_rad"] *= 180 / kPi;
         });
       },
       "wheels.rl_unit"},
      {"GNSS time x10", "",
       [](const fs::path& log) { edit_csv(log / "gnss.csv", [](Row& r) { r["t"] *= 10; }); },
       "time.scale"},
      {"GNSS clock +0.6 s", "", shift("gnss.csv", 0.6), "time.gnss_offset"},
      {"IMU clock -0.8 s", "", shift("imu.csv", -0.8), "time.imu_offset"},
      {"GNSS fixes repeated", "",
       [](const fs::path& log) {
         int row = 0;
         double x = 0, y = 0;
         edit_csv(log / "gnss.csv", [&](Row& r) {
           if (row++ % 4 == 0) {
             x = r["x"];
             y = r["y"];
           }
           r["x"] = x;
           r["y"] = y;
         });
       },
       "gnss.repeated"},
      {"gyro negated", "",
       [](const fs::path& log) { edit_csv(log / "imu.csv", [](Row& r) { r["wz"] = -r["wz"]; }); },
       "imu.yaw_sign"},
      {"gyro in deg/s", "",
       [](const fs::path& log) { edit_csv(log / "imu.csv", [](Row& r) { r["wz"] *= 180 / kPi; }); },
       "imu.yaw_unit"},
      {"ay negated", "",
       [](const fs::path& log) { edit_csv(log / "imu.csv", [](Row& r) { r["ay"] = -r["ay"]; }); },
       "imu.ay_sign"},
      {"ax and ay swapped", "",
       [](const fs::path& log) {
         edit_csv(log / "imu.csv", [](Row& r) { std::swap(r["ax"], r["ay"]); });
       },
       "imu.axes_swapped"},
      {"compass heading", "",
       [](const fs::path& log) {
         edit_csv(log / "heading.csv",
                  [](Row& r) { r["heading"] = std::remainder(kPi / 2 - r["heading"], 2 * kPi); });
       },
       "heading.convention"},
      {"heading in degrees", "",
       [](const fs::path& log) {
         edit_csv(log / "heading.csv",
                  [](Row& r) { r["heading"] = std::fmod(r["heading"] * 180 / kPi + 360, 360); });
       },
       "heading.degrees"},
      {"x and y swapped", "",
       [](const fs::path& log) {
         edit_csv(log / "gnss.csv", [](Row& r) { std::swap(r["x"], r["y"]); });
       },
       "gnss.mirrored"},
      {"lat and lon swapped", "--gnss-output latlon",
       [](const fs::path& log) {
         edit_csv(log / "gnss.csv", [](Row& r) { std::swap(r["lat"], r["lon"]); });
       },
       "gnss.mirrored"},
  };
}

}  // namespace odocal::testing
