// import csv --sync with a drive force column logged on a late clock: the doctor's estimate moves
// the column onto the wheels' clock, and the imported log is the simulator's again.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "../support/temp_log_dir.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/log_diagnosis.hpp"
#include "odocal/io/csv_import.hpp"
#include "odocal/io/log_reader.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

using testing::TempLogDir;

constexpr double kLateS = 0.3;

// The simulated log's files as a logger's, the force in a file of its own whose stamps are
// kLateS late, and a map that reads them.
void write_logger(const TempLogDir& src, const sim::SimulatedDrive& drive,
                  const sim::Scenario& scenario, const Log& truth_log) {
  write_simulated_log(drive, scenario, src.path());
  std::string torque = "stamp,force\n";
  for (std::size_t k = 0; k < truth_log.wheels.size(); ++k)
    torque += fmt::format("{:.4f},{:.1f}\n", truth_log.wheels.t_s[k] + kLateS,
                          truth_log.wheels.drive_force_n[k]);
  src.write("torque.csv", torque);
  const VehicleConfig& v = truth_log.vehicle;
  src.write(
      "map.yaml",
      fmt::format("vehicle: {{track_width_m: {}, circumference_rl_m: {}, circumference_rr_m: {}, "
                  "ticks_per_rev: 96, counter_bits: 16, wheelbase_m: 2.7}}\n"
                  "streams:\n"
                  "  wheels: {{file: wheels.csv, time: {{column: t, unit: s}},"
                  " rl: {{column: rl_ticks, unit: ticks}}, rr: {{column: rr_ticks, unit: ticks}},"
                  " drive_force: {{file: torque.csv, time: {{column: stamp, unit: s}},"
                  " column: force, unit: N}}}}\n"
                  "  gnss: {{file: gnss.csv, time: {{column: t, unit: s}}, position: local,"
                  " x: {{column: x, unit: m}}, y: {{column: y, unit: m}}}}\n"
                  "  imu: {{file: imu.csv, time: {{column: t, unit: s}}, ax: {{column: ax, unit: "
                  "m/s^2}}, ay: {{column: ay, unit: m/s^2}}, wz: {{column: wz, unit: rad/s}}}}\n",
                  v.track_width_m, v.circumference_rl_m, v.circumference_rr_m));
}

TEST(DriveForceSync, TheImportMovesALateForceOntoTheWheelsClock) {
  const TempLogDir src;
  sim::Scenario scenario = load_scenario("urban");
  scenario.route.laps = 1;
  scenario.wheels.drive_force_sigma_n = 0.0;  // the bus's force as it was: compared row by row
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log simulated = simulated_log(drive);
  write_logger(src, drive, scenario, simulated);

  const TempLogDir plain;
  import_csv(src.file("map.yaml"), src.path(), plain.path());
  EXPECT_TRUE(diagnose_log(read_log(plain.path())).blocking());

  const TempLogDir synced;
  const ImportSummary summary =
      import_csv(src.file("map.yaml"), src.path(), synced.path(), {.sync_clocks = true});
  std::string notes;
  for (const std::string& note : summary.notes) notes += note + "\n";
  const auto at = notes.find("drive_force_n: moved by ");
  ASSERT_NE(at, std::string::npos) << notes;
  EXPECT_NEAR(std::stod(notes.substr(at + 24)), -kLateS, 0.04) << notes;
  const Log log = read_log(synced.path());
  EXPECT_FALSE(diagnose_log(log).blocking());
  // Row by row the simulator's force again, to the estimate's few hundredths of a second.
  // (The rows before the force's first stamp are not kept: both logs start kLateS in.)
  const Log unsynced = read_log(plain.path());
  ASSERT_EQ(log.wheels.size(), unsynced.wheels.size());
  double sum = 0.0, plain_sum = 0.0;
  for (std::size_t k = 0; k < log.wheels.size(); ++k) {
    const double truth = *interpolate_linear(simulated.wheels.t_s, simulated.wheels.drive_force_n,
                                             log.wheels.t_s[k]);
    sum += std::abs(log.wheels.drive_force_n[k] - truth);
    plain_sum += std::abs(unsynced.wheels.drive_force_n[k] - truth);
  }
  EXPECT_LT(sum, 0.2 * plain_sum);
}

}  // namespace
}  // namespace odocal
