// The doctor's fault-injection matrix: each input mistake, injected into a clean simulated drive
// (and into the shipped real-car example where it has the streams), is found by the check that
// names it; the clean logs give no blocking finding.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <sstream>

#include "../support/run_cli.hpp"
#include "../support/temp_log_dir.hpp"
#include "odocal/io/log_doctor.hpp"

namespace odocal {
namespace {

namespace fs = std::filesystem;
using testing::read_text_file;
using testing::run_cli;
using testing::TempLogDir;
constexpr double kPi = std::numbers::pi;

using Row = std::map<std::string, double>;

// Rewrites a CSV file row by row (every column as a number).
void edit_csv(const fs::path& file, const std::function<void(Row&)>& edit,
              std::vector<std::string> header = {}) {
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

std::string checks(const Diagnosis& diagnosis, bool blocking_only) {
  std::string list;
  for (const Finding& f : diagnosis.findings) {
    if (!blocking_only || f.severity == FindingSeverity::kBlocking) list += f.check + " ";
  }
  return list;
}

struct Fault {
  const char* name;
  const char* simulate;  // extra simulate flags
  std::function<void(const fs::path&)> inject;
  const char* expected_check;
};

// Multiplies one number in the log's vehicle.yaml.
void scale_vehicle_value(const fs::path& log, const std::string& key, double factor) {
  std::string yaml = read_text_file((log / "vehicle.yaml").string());
  const auto at = yaml.find(key + ": ") + key.size() + 2;
  const auto end = yaml.find('\n', at);
  yaml.replace(at, end - at, fmt::format("{:.6f}", factor * std::stod(yaml.substr(at, end - at))));
  std::ofstream(log / "vehicle.yaml") << yaml;
}

double wrap16(double ticks) { return std::fmod(std::fmod(ticks, 65536.0) + 65536.0, 65536.0); }

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

class DoctorMatrix : public ::testing::Test {
 protected:
  static fs::path simulated(const TempLogDir& dir, const std::string& flags) {
    const fs::path log = dir.path() / "log";
    const auto run =
        run_cli(fmt::format("simulate --laps 1 --seed 3 {} --out {}", flags, log.string()));
    EXPECT_EQ(run.status, 0) << run.err;
    return log;
  }
};

TEST_F(DoctorMatrix, CleanSimulatedLogsHaveNoBlockingFinding) {
  for (const char* flags : {"", "--ideal", "--wheel-output radps", "--gnss-output latlon"}) {
    const TempLogDir dir;
    const Diagnosis diagnosis = doctor_log(simulated(dir, flags));
    EXPECT_FALSE(diagnosis.blocking()) << flags << ": " << checks(diagnosis, true);
  }
}

TEST_F(DoctorMatrix, EveryInjectedFaultIsFoundByItsCheck) {
  for (const Fault& fault : faults()) {
    const TempLogDir dir;
    const fs::path log = simulated(dir, fault.simulate);
    fault.inject(log);
    const Diagnosis diagnosis = doctor_log(log);
    EXPECT_TRUE(diagnosis.blocking()) << fault.name;
    EXPECT_NE(checks(diagnosis, true).find(fault.expected_check), std::string::npos)
        << fault.name << ": found " << checks(diagnosis, false);
  }
}

TEST_F(DoctorMatrix, TheRealCarExampleIsCleanAndItsFaultsAreFound) {
  const fs::path example = fs::path(ODOCAL_SOURCE_DIR) / "examples" / "figure-eight";
  EXPECT_FALSE(doctor_log(example).blocking()) << checks(doctor_log(example), true);
  const TempLogDir dir;
  const fs::path log = dir.path() / "log";
  fs::copy(example, log);
  edit_csv(log / "wheels.csv", [](Row& r) { std::swap(r["rl_ticks"], r["rr_ticks"]); });
  EXPECT_NE(checks(doctor_log(log), true).find("wheels.swapped"), std::string::npos)
      << checks(doctor_log(log), false);
}

// A real car (comma2k19, imported with the shipped map): clean, and its faults found. The drive
// is nearly straight, so left/right cannot be checked there (the doctor says so).
TEST(DoctorRealLog, Comma2k19IsCleanAndItsFaultsAreFound) {
  const fs::path data = fs::path(ODOCAL_SOURCE_DIR) / "../shared/data/real/comma2k19";
  if (!fs::exists(data / "wheel_speeds.csv")) GTEST_SKIP() << "shared data absent: " << data;
  const TempLogDir dir;
  const fs::path log = dir.path() / "log";
  ASSERT_EQ(run_cli(fmt::format("import csv --map {}/examples/comma2k19/map.yaml --in {} --out {}",
                                ODOCAL_SOURCE_DIR, data.string(), log.string()))
                .status,
            0);
  EXPECT_FALSE(doctor_log(log).blocking()) << checks(doctor_log(log), true);
  const std::string wheels = read_text_file((log / "wheels.csv").string());
  edit_csv(log / "wheels.csv", [](Row& r) { r["rl_mps"] = -r["rl_mps"]; });
  EXPECT_NE(checks(doctor_log(log), true).find("wheels.rl_sign"), std::string::npos)
      << checks(doctor_log(log), false);
  std::ofstream(log / "wheels.csv") << wheels;
  edit_csv(log / "gnss.csv", [](Row& r) { r["t"] += 0.7; });
  EXPECT_NE(checks(doctor_log(log), true).find("time.gnss_offset"), std::string::npos)
      << checks(doctor_log(log), false);
}

TEST(DoctorCli, ExitsThreeOnABlockingFindingAndWritesJson) {
  const TempLogDir dir;
  ASSERT_EQ(run_cli("simulate --laps 1 --out " + dir.file("log")).status, 0);
  const auto clean = run_cli("doctor " + dir.file("log") + " --json " + dir.file("d.json"));
  EXPECT_EQ(clean.status, 0) << clean.out << clean.err;
  EXPECT_NE(read_text_file(dir.file("d.json")).find("\"blocking\": false"), std::string::npos);
  edit_csv(dir.path() / "log" / "imu.csv", [](Row& r) { r["wz"] = -r["wz"]; });
  const auto bad = run_cli("doctor " + dir.file("log"));
  EXPECT_EQ(bad.status, 3);
  EXPECT_NE(bad.out.find("imu.yaw_sign"), std::string::npos) << bad.out;
  // calibrate runs the blocking checks first; --force skips them.
  const auto refused = run_cli("calibrate " + dir.file("log"));
  EXPECT_EQ(refused.status, 3);
  EXPECT_NE(refused.err.find("odocal doctor"), std::string::npos) << refused.err;
  const auto forced = run_cli("calibrate --force " + dir.file("log"));
  EXPECT_EQ(forced.err.find("odocal doctor"), std::string::npos) << forced.err;
}

// Garbage values: every bad column counted with its first line, before the reader's error (exit
// 2); denormals alone are a warning (exit 0).
TEST(DoctorCli, CountsGarbageValuesPerColumn) {
  const TempLogDir dir;
  ASSERT_EQ(run_cli("simulate --laps 1 --ideal --out " + dir.file("log")).status, 0);
  const fs::path imu = dir.path() / "log" / "imu.csv";
  std::string text = read_text_file(imu.string());
  // Rows 2 and 3 of imu.csv (lines 3 and 4) get a denormal yaw rate.
  std::vector<std::string> lines;
  for (std::size_t at = 0, next; at < text.size(); at = next + 1) {
    next = text.find('\n', at);
    lines.push_back(text.substr(at, next - at));
  }
  for (std::size_t line : {2, 3})
    lines[line] = lines[line].substr(0, lines[line].rfind(',')) + ",4.9e-320";
  std::string joined;
  for (const std::string& line : lines) joined += line + "\n";
  std::ofstream(imu) << joined;
  const auto denormal = run_cli("doctor " + dir.file("log"));
  EXPECT_EQ(denormal.status, 0) << denormal.out << denormal.err;
  EXPECT_NE(denormal.out.find("imu.csv column 'wz' has 2 denormal value(s): 2 of"),
            std::string::npos)
      << denormal.out;
  EXPECT_NE(denormal.out.find("the first at line 3"), std::string::npos) << denormal.out;

  edit_csv(dir.path() / "log" / "gnss.csv", [](Row& r) {
    if (r["t"] > 10.0 && r["t"] < 10.5) r["x"] = NAN;
  });
  const auto not_finite = run_cli("doctor " + dir.file("log"));
  EXPECT_EQ(not_finite.status, 2);
  EXPECT_NE(not_finite.out.find("gnss.csv column 'x' has"), std::string::npos) << not_finite.out;
  EXPECT_NE(not_finite.out.find("(data.not_finite)"), std::string::npos) << not_finite.out;
  EXPECT_NE(not_finite.err.find("gnss.csv:"), std::string::npos) << not_finite.err;
}

}  // namespace
}  // namespace odocal
