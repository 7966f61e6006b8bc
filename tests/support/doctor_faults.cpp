#include "doctor_faults.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "odocal/error.hpp"
#include "odocal/io/log_doctor.hpp"
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

void drop_rows_between(const fs::path& file, double from_s, double to_s) {
  std::istringstream in(read_text_file(file.string()));
  std::string line, out;
  std::getline(in, line);
  out = line + "\n";
  while (std::getline(in, line)) {
    const double t = std::stod(line.substr(0, line.find(',')));
    if (t < from_s || t >= to_s) out += line + "\n";
  }
  std::ofstream(file) << out;
}

namespace {

// Leaves the IMU's place out of the log's vehicle.yaml (its imu_x_m and imu_y_m lines).
void drop_imu_place(const fs::path& log) {
  std::istringstream lines(read_text_file((log / "vehicle.yaml").string()));
  std::string kept;
  for (std::string line; std::getline(lines, line);)
    if (!line.starts_with("imu_")) kept += line + "\n";
  std::ofstream(log / "vehicle.yaml") << kept;
}

// Multiplies one number in the log's vehicle.yaml.
void scale_vehicle_value(const fs::path& log, const std::string& key, double factor) {
  std::string yaml = read_text_file((log / "vehicle.yaml").string());
  const auto at = yaml.find(key + ": ") + key.size() + 2;
  const auto end = yaml.find('\n', at);
  yaml.replace(at, end - at, fmt::format("{:.6f}", factor * std::stod(yaml.substr(at, end - at))));
  std::ofstream(log / "vehicle.yaml") << yaml;
}

double wrap16(double ticks) { return std::fmod(std::fmod(ticks, 65536.0) + 65536.0, 65536.0); }

// The first and last time of a CSV file's t column.
std::pair<double, double> time_span(const fs::path& file) {
  double first = NAN, last = NAN;
  edit_csv(file, [&](Row& r) {
    if (std::isnan(first)) first = r["t"];
    last = r["t"];
  });
  return {first, last};
}

// Leaves out the rows of `file` whose time lies in [from, to), given as shares of its span.
void drop_rows(const fs::path& file, double from_share, double to_share) {
  const auto [first, last] = time_span(file);
  drop_rows_between(file, first + from_share * (last - first), first + to_share * (last - first));
}

// Sets `column` of `count` rows from the middle of `file` on to `value`.
void overwrite_cells(const fs::path& file, const std::string& column, double value, int count) {
  const auto [first, last] = time_span(file);
  const double middle = 0.5 * (first + last);
  int written = 0;
  edit_csv(file, [&](Row& r) {
    if (r["t"] >= middle && written < count) {
      r[column] = value;
      ++written;
    }
  });
}

}  // namespace

Diagnosis doctor_directory(const fs::path& log) {
  try {
    return doctor_log(log);
  } catch (const InputError&) {
    return {scan_stream_values(log), 0.0};
  }
}

bool found(const Diagnosis& diagnosis, const Fault& fault) {
  return std::any_of(diagnosis.findings.begin(), diagnosis.findings.end(), [&](const Finding& f) {
    return f.check == fault.expected_check && f.severity == fault.expected_severity;
  });
}

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
      {"track 10 % short", "",
       [](const fs::path& log) { scale_vehicle_value(log, "track_width_m", 1 / 1.1); },
       "vehicle.track_width", FindingSeverity::kWarning},
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
      {"IMU clock +0.2 s", "", shift("imu.csv", 0.2), "time.imu_offset"},
      // Below the blocking offset the yaw rates still show it where they match closely: the tyre
      // model's force comes from the accelerometer at the wheels' time.
      {"IMU clock +0.1 s", "", shift("imu.csv", 0.1), "time.imu_offset", FindingSeverity::kWarning},
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
      // The realistic car's IMU sits at its centre of gravity, 1.45 m ahead of the rear axle; the
      // ideal one reads the axle's motion. Stated wrong either way, layer 1 misreads its turns.
      {"IMU's place unstated", "--scenario urban", drop_imu_place, "imu.place",
       FindingSeverity::kWarning},
      {"IMU's place stated where it is not", "--scenario urban --ideal",
       [](const fs::path& log) {
         std::ofstream(log / "vehicle.yaml", std::ios::app) << "imu_x_m: 1.45\n";
       },
       "imu.place", FindingSeverity::kWarning},
      // An IMU left of the axle reads its turns' centripetal -w^2 y: stated 1 m left of an IMU at
      // the axle, the lateral readings of the urban corners put it back there (y 0.01 +- 0.04 m).
      {"IMU's side stated where it is not", "--scenario urban --ideal",
       [](const fs::path& log) {
         std::ofstream(log / "vehicle.yaml", std::ios::app) << "imu_y_m: 1.0\n";
       },
       "imu.place", FindingSeverity::kWarning},
      // An antenna left of the axle runs y w slower in a left turn: stated 0.6 m left of one over
      // the axle, the Doppler speed of the urban corners puts it back there.
      {"antenna's side stated where it is not", "--scenario urban --ideal --gnss-speed-sigma 0.05",
       [](const fs::path& log) {
         std::ofstream(log / "vehicle.yaml", std::ios::app) << "gnss_y_m: 0.6\n";
       },
       "gnss.place", FindingSeverity::kWarning},
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
      {"heading mounted 3 deg off", "",
       [](const fs::path& log) {
         edit_csv(log / "heading.csv", [](Row& r) { r["heading"] += 0.05; });
       },
       "heading.offset", FindingSeverity::kWarning},
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
      {"GNSS time in ms read as s", "",
       [](const fs::path& log) { edit_csv(log / "gnss.csv", [](Row& r) { r["t"] *= 1000; }); },
       "time.scale"},
      {"not-a-number cells", "",
       [](const fs::path& log) { overwrite_cells(log / "imu.csv", "ax", NAN, 3); },
       "data.not_finite"},
      {"denormal cells", "",
       [](const fs::path& log) { overwrite_cells(log / "imu.csv", "ay", 4.9e-322, 3); },
       "data.denormal", FindingSeverity::kWarning},
      {"wheel gap 2 s", "",
       [](const fs::path& log) {
         const auto [first, last] = time_span(log / "wheels.csv");
         drop_rows(log / "wheels.csv", 0.4, 0.4 + 2.0 / (last - first));
       },
       "wheels.gaps", FindingSeverity::kWarning},
      {"GNSS outage 20 s", "",
       [](const fs::path& log) {
         const auto [first, last] = time_span(log / "gnss.csv");
         drop_rows(log / "gnss.csv", 0.4, 0.4 + 20.0 / (last - first));
       },
       "gnss.gaps", FindingSeverity::kNote},
      {"IMU stops half way", "", [](const fs::path& log) { drop_rows(log / "imu.csv", 0.5, 2.0); },
       "time.span", FindingSeverity::kWarning},
      {"gyro bias 1 deg/s", "",
       [](const fs::path& log) { edit_csv(log / "imu.csv", [](Row& r) { r["wz"] += kPi / 180; }); },
       "imu.gyro_bias", FindingSeverity::kNote},
      {"wheel rate biases", "--wheel-output radps",
       [](const fs::path& log) {
         edit_csv(log / "wheels.csv", [](Row& r) {
           r["rl_radps"] -= 0.33 * kPi / 180;
           r["rr_radps"] += 1.22 * kPi / 180;
         });
       },
       "wheels.rate_bias", FindingSeverity::kNote},
      {"no GNSS altitude", "",
       [](const fs::path& log) {
         std::ifstream in(log / "gnss.csv");
         std::string header;
         std::getline(in, header);
         in.close();
         std::vector<std::string> kept;
         std::stringstream names(header);
         for (std::string name; std::getline(names, name, ',');)
           if (name != "alt") kept.push_back(name);
         edit_csv(
             log / "gnss.csv", [](Row&) {}, kept);
       },
       "gnss.altitude", FindingSeverity::kNote},
  };
}

}  // namespace odocal::testing
