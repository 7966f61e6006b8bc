// The physical tyre terms take the accelerometer's force at the centre of gravity: an IMU mounted
// elsewhere, where vehicle.yaml says it is, calibrates as one at the centre of gravity does, and
// taken to be at the centre of gravity it does not (simulated truth, ../shared's Hockenheim).

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

const std::string kHockenheimTrack =
    std::string(ODOCAL_SOURCE_DIR) + "/../shared/data/tracks/hockenheim/track.csv";

// c_RL's error (m) of `auto` on 3 laps of Hockenheim, rear-driven, the grip-sharing driver,
// seed 1, the IMU mounted `mount_x_m` ahead of the centre of gravity; vehicle.yaml states the IMU
// `stated_x_m` from the rear axle where given, else where the simulator mounted it.
double error_rl_m(double mount_x_m, std::optional<double> stated_x_m = std::nullopt) {
  sim::Scenario scenario = load_scenario("circuit");
  use_track_file(scenario, kHockenheimTrack);
  scenario.driver.friction_ellipse = true;
  scenario.driver.max_power_wpkg = 80.0;
  scenario.vehicle.wear_rl_mm = 1.5;
  scenario.vehicle.wear_rr_mm = 1.0;
  scenario.imu.mount_x_m = mount_x_m;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  Log log = simulated_log(drive);
  if (stated_x_m) log.vehicle.imu_position_m = Eigen::Vector2d(*stated_x_m, 0.0);
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  const BatchSummary result = calibrate_batch(log, options);
  EXPECT_EQ(result.tyre_selection.chosen, "physical") << result.full_report();
  return result.estimate.circumference_rl_m - drive.true_params.circumference_rl_m;
}

// Measured (2026-12-06): at the centre of gravity +0.11 mm; 1.5 m ahead of it and stated so
// +0.10 mm; the same taken as at the centre of gravity (1.45 m from the axle) +2.24 mm, its
// whole-log dead reckoning against the truth 28 m where the other two make 18 m. Seeds 2 and 3
// alike (-0.03 / -0.01 / +2.31 mm, +0.03 / -0.01 / +2.46 mm).
TEST(ImuPlaceBatch, AnImuAheadOfTheCentreOfGravityCalibratesAsOneThereWhereVehicleYamlSaysSo) {
  if (!std::filesystem::exists(kHockenheimTrack))
    GTEST_SKIP() << "shared data absent: " << kHockenheimTrack;
  const double at_cg = error_rl_m(0.0);
  EXPECT_NEAR(error_rl_m(1.5), at_cg, 3e-4);
  EXPECT_GT(error_rl_m(1.5, 1.45) - at_cg, 1.5e-3);
}

}  // namespace
}  // namespace odocal
