// The accelerometer's forward offset: each stop's mean reading (its settling seconds left out),
// their mean and how well the stops' scatter knows it, and its removal where a log is prepared.

#include "odocal/estimation/accelerometer_offset.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../support/forward_offset_removed.hpp"
#include "odocal/estimation/log_preparation.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

// 100 Hz from 0 to 20 s: 1 m/s^2 in each stop's first and last second, `inside` between.
ImuStream stepped_imu(double inside) {
  ImuStream imu;
  for (int k = 0; k <= 2000; ++k) {
    const double t = 0.01 * k;
    imu.t_s.push_back(t);
    const bool settling = t < 1.0 || (t > 9.0 && t < 11.0) || t > 19.0;
    imu.ax_mps2.push_back(settling ? 1.0 : inside);
    imu.ay_mps2.push_back(0.0);
    imu.wz_radps.push_back(0.0);
  }
  return imu;
}

TEST(AccelerometerOffset, EachStopReadsWithoutItsSettlingSeconds) {
  const ImuStream imu = stepped_imu(0.25);
  const std::vector<StopReading> readings =
      standing_forward_readings(imu, {{0.0, 10.0}, {10.0, 20.0}, {4.0, 5.5}});
  ASSERT_EQ(readings.size(), 2u);  // the 1.5 s stop keeps nothing once settled
  for (const StopReading& stop : readings) {
    EXPECT_NEAR(stop.forward_mps2, 0.25, 1e-12);
    EXPECT_NEAR(stop.standing_s, 8.0, 1e-12);
  }
}

TEST(AccelerometerOffset, TheStopsScatterSaysHowWellTheirMeanIsKnown) {
  EXPECT_FALSE(accelerometer_offset({}).has_value());
  // Too few stops to show their slopes' scatter: the unmeasured sigma.
  const auto two = accelerometer_offset({{0.1, 5.0}, {0.3, 5.0}});
  ASSERT_TRUE(two.has_value());
  EXPECT_NEAR(two->forward_mps2, 0.2, 1e-12);
  EXPECT_EQ(two->sigma_mps2, kUnmeasuredForwardOffsetSigmaMps2);
  // Stops of equal weight: the sample deviation 0.1291 over the root of 4, with the common
  // slope's 0.005.
  const auto four = accelerometer_offset({{0.1, 5.0}, {0.2, 5.0}, {0.3, 5.0}, {0.4, 5.0}});
  ASSERT_TRUE(four.has_value());
  EXPECT_NEAR(four->forward_mps2, 0.25, 1e-12);
  EXPECT_NEAR(four->sigma_mps2, std::hypot(std::sqrt(0.05 / 3.0) / 2.0, 0.005), 1e-12);
  EXPECT_EQ(four->stops, 4u);
  EXPECT_NEAR(four->standing_s, 20.0, 1e-12);
  // Stops that agree leave the common slope's floor.
  const auto level = accelerometer_offset({{0.3, 1.0}, {0.3, 4.0}, {0.3, 9.0}});
  EXPECT_NEAR(level->sigma_mps2, 0.005, 1e-12);
  // A short stop weighs by its time; one that stands past 10 s no more than a 10 s one, so that
  // a long stop on a hill does not outvote the rest.
  EXPECT_NEAR(accelerometer_offset({{0.4, 2.0}, {0.0, 6.0}, {0.0, 2.0}})->forward_mps2, 0.08,
              1e-12);
  EXPECT_NEAR(accelerometer_offset({{0.5, 300.0}, {0.0, 10.0}, {0.0, 12.0}})->forward_mps2,
              0.5 / 3.0, 1e-12);
}

// One lap of the realistic circuit that stands 30 s at its start and its end, its accelerometer
// reading `offset` more forward.
Log standing_lap(double offset) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.route.laps = 1;
  scenario.driver.start_dwell_s = 30.0;
  Log log = simulated_log(sim::simulate(scenario));
  for (double& ax : log.imu->ax_mps2) ax += offset;
  return log;
}

TEST(AccelerometerOffset, StandingOutOfItsSigmaItIsRemovedAndWithinLeftIn) {
  EXPECT_TRUE(accelerometer_offset({{0.35, 5.0}})->removed);  // beyond 3 x 0.1
  EXPECT_FALSE(accelerometer_offset({{0.25, 5.0}})->removed);
  EXPECT_FALSE(accelerometer_offset({{0.015, 5.0}, {0.015, 5.0}, {0.015, 5.0}})->removed);
  EXPECT_TRUE(accelerometer_offset({{0.025, 5.0}, {0.025, 5.0}, {0.025, 5.0}})->removed);
  AccelerometerOffset offset;
  offset.forward_mps2 = 0.03;
  offset.sigma_mps2 = 0.04;
  EXPECT_NEAR(offset.left_sigma_mps2(), 0.05, 1e-12);  // left in: itself and its sigma
  offset.removed = true;
  EXPECT_EQ(offset.left_sigma_mps2(), 0.04);
}

TEST(AccelerometerOffset, IsTakenOutOfTheLogWhereItIsPrepared) {
  const Log log = standing_lap(0.5);
  LogPreparation done;
  const std::optional<Log> prepared = prepare_log(log, CalibrationOptions{}, done);
  ASSERT_TRUE(prepared.has_value());
  ASSERT_TRUE(done.accelerometer_offset.has_value());
  EXPECT_EQ(done.accelerometer_offset->stops, 2u);
  EXPECT_NEAR(done.accelerometer_offset->forward_mps2, 0.5, 0.02);
  EXPECT_EQ(done.accelerometer_offset->sigma_mps2, kUnmeasuredForwardOffsetSigmaMps2);
  EXPECT_TRUE(done.accelerometer_offset->removed);
  // Two stops are too few to know the offset by: the lap, which ends where it began, measures
  // it over the drive (drive_forward_offset_test.cpp), and that is what is removed.
  ASSERT_TRUE(done.drive_forward_offset.has_value());
  const double removed = done.drive_forward_offset->forward_mps2;
  EXPECT_NEAR(removed, 0.5, 3.0 * done.drive_forward_offset->sigma_mps2);
  EXPECT_NE(done.describe().find("accelerometer's forward offset removed over"), std::string::npos)
      << done.describe();
  testing::expect_forward_offset_removed(*log.imu, *prepared->imu, removed);

  // The clean lap's reading is within its noise: left in (the log not copied for it).
  LogPreparation clean;
  prepare_log(standing_lap(0.0), CalibrationOptions{}, clean);
  ASSERT_TRUE(clean.accelerometer_offset.has_value());
  EXPECT_FALSE(clean.accelerometer_offset->removed);
  EXPECT_NE(clean.describe().find("within its noise, left in"), std::string::npos);

  CalibrationOptions kept;
  kept.remove_accelerometer_offset = false;
  LogPreparation untouched;
  const std::optional<Log> without = prepare_log(log, kept, untouched);
  EXPECT_FALSE(untouched.accelerometer_offset.has_value());
  ASSERT_TRUE(without.has_value());  // it starts at first motion all the same
  const ImuStream& in = *log.imu;
  const auto first = std::lower_bound(in.t_s.begin(), in.t_s.end(), without->imu->t_s.front());
  EXPECT_EQ(without->imu->ax_mps2.front(),
            in.ax_mps2[static_cast<std::size_t>(first - in.t_s.begin())]);
}

// Without 3 stops: the forward reading while driving straight less the wheels' acceleration. On
// the realistic circuit's lap the rear-driven car's changing slip leaves a tenth of a m/s^2 in
// it; an offset shifts it by itself (the median of shifted bins).
TEST(AccelerometerOffset, WhileDrivingStraightItIsReadBeyondTheWheelsAcceleration) {
  Log log = standing_lap(0.0);
  const OdometryParams nominal = log.vehicle.nominal_params();
  const std::optional<double> clean = driving_forward_offset(log, nominal);
  ASSERT_TRUE(clean.has_value());
  EXPECT_LT(std::abs(*clean), 0.15);
  for (double& ax : log.imu->ax_mps2) ax -= 0.7;
  const std::optional<double> pitched = driving_forward_offset(log, nominal);
  ASSERT_TRUE(pitched.has_value());
  EXPECT_NEAR(*pitched - *clean, -0.7, 1e-9);
  log.imu.reset();
  EXPECT_FALSE(driving_forward_offset(log, nominal).has_value());
}

}  // namespace
}  // namespace odocal
