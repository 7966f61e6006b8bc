// The tyres' force from the log (wheels.csv's drive_force_n) through the batch, where the
// accelerometer misleads the physical terms most: 3 laps of Hockenheim, rear-driven, with the
// circuit's driver, whose car fishtails once a lap in a fast kink with its inner rear wheel near
// the grip (docs/tyre-model.md, "The drive force").

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

const std::string kHockenheimTrack =
    std::string(ODOCAL_SOURCE_DIR) + "/../shared/data/tracks/hockenheim/track.csv";

struct Fit {
  double error_rl_m, sigma_rl_m;
  std::string report;
};

Fit calibrate_kink_laps(double drive_force_sigma_n) {
  sim::Scenario scenario = load_scenario("circuit");
  use_track_file(scenario, kHockenheimTrack);
  scenario.vehicle.wear_rl_mm = 1.5;
  scenario.vehicle.wear_rr_mm = 1.0;
  scenario.wheels.drive_force_sigma_n = drive_force_sigma_n;
  // Built on the simulator's force in steps (actuator_time_constant_s 0, before 2026-12-05), whose
  // kink left the accelerometer's fit beyond 4 mm; with the lag it is 0.5 mm on seed 1
  // (docs/simulator.md).
  scenario.dynamics.actuator_time_constant_s = 0.0;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  BatchOptions options;
  options.max_sigma_circumference_m = 0.05;  // score the estimate: its sigma is 10-20 mm
  const BatchSummary fit = calibrate_batch(simulated_log(drive), options);
  return {fit.estimate.circumference_rl_m - drive.true_params.circumference_rl_m, fit.sigma_rl_m(),
          fit.full_report()};
}

TEST(DriveForceBatch, TheTyresForceTakesTheKinksErrorOffTheCircumference) {
  if (!std::filesystem::exists(kHockenheimTrack))
    GTEST_SKIP() << "shared data absent: " << kHockenheimTrack;
  // With the accelerometer alone the force the physical terms take in the kink is the body's
  // acceleration, which the fishtailing car's yaw and steered front wheels take apart from the
  // tyres' force: c_RL 2.6 mm low (5.5 mm before the grip limit and the cornering drag along the
  // front wheels' steer, docs/tyre-model.md). The force that the tyres transmit takes a part of
  // that off (1.9 mm; 1.4 mm with the force exact: what is left is not the force).
  const Fit read = calibrate_kink_laps(-1.0);
  const Fit given = calibrate_kink_laps(100.0);
  EXPECT_GT(std::abs(read.error_rl_m), 2e-3) << read.report;
  EXPECT_LT(std::abs(given.error_rl_m), 0.8 * std::abs(read.error_rl_m)) << given.report;
  EXPECT_LT(std::abs(given.error_rl_m), 3.0 * given.sigma_rl_m) << given.report;
}

}  // namespace
}  // namespace odocal
