// The accelerometer's forward offset measured over the drive (drive_forward_offset.hpp): the
// speed gained cancels the driver's acceleration and the wheels' slip, an offset shifts the
// measure by itself, an IMU gap splits the drive, and a slope the drive cannot know leaves it
// unmeasured. Checked against the simulator's accelerometer, which has no offset.

#include "odocal/estimation/drive_forward_offset.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../support/forward_offset_removed.hpp"
#include "odocal/estimation/accelerometer_offset.hpp"
#include "odocal/estimation/log_preparation.hpp"
#include "odocal/estimation/log_window.hpp"
#include "odocal/estimation/prepared_blocks.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

constexpr double kWhole = 1e12;

// One lap of a built-in scenario, realistic, its accelerometer reading `offset` more forward.
Log lap(const char* scenario_name, double offset, unsigned seed = 1) {
  sim::Scenario scenario = load_scenario(scenario_name);
  scenario.route.laps = 1;
  scenario.seeds.noise = scenario.seeds.trajectory = seed;
  Log log = simulated_log(sim::simulate(scenario));
  for (double& ax : log.imu->ax_mps2) ax += offset;
  return log;
}

DriveForwardOffset measured(const Log& log, DriveSlope slope) {
  const DriveForwardSums sums =
      drive_forward_sums(log, log.vehicle.nominal_params(), -kWhole, kWhole);
  const auto offset = drive_forward_offset(sums, log.vehicle.body_geometry(), slope);
  EXPECT_TRUE(offset.has_value());
  return offset.value_or(DriveForwardOffset{});
}

TEST(DriveForwardOffset, ALapOfTheRealisticCircuitReadsNoOffsetWithinItsSigma) {
  // The rear-driven car's slip, which driving straight reads as -0.1 m/s^2 (the driver's
  // acceleration less the wheels'), cancels over the lap; the turns' w^2 b and side slip do not
  // and are accounted for. Three seeds of driver and noise.
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const Log clean = lap("circuit", 0.0, seed);
    const DriveForwardOffset offset = measured(clean, DriveSlope::kClosedLoop);
    EXPECT_LT(std::abs(offset.forward_mps2), offset.sigma_mps2) << "seed " << seed;
    EXPECT_LT(offset.sigma_mps2, 0.6 * kUnmeasuredForwardOffsetSigmaMps2);
    EXPECT_FALSE(offset.removed);
    EXPECT_GT(offset.distance_m, 4000.0);
  }
}

// An IMU mounted 1.5 m ahead of the centre of gravity reads each turn's -w^2 x there too: where
// vehicle.yaml says so, the lap reads no offset; taken as at the centre of gravity, the turns
// read as one.
TEST(DriveForwardOffset, AnImuAheadOfTheCentreOfGravityIsMeasuredWhereVehicleYamlMountsIt) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.route.laps = 1;
  scenario.imu.mount_x_m = 1.5;
  Log log = simulated_log(sim::simulate(scenario));
  const DriveForwardOffset stated = measured(log, DriveSlope::kClosedLoop);
  log.vehicle.imu_position_m.reset();
  const DriveForwardOffset unstated = measured(log, DriveSlope::kClosedLoop);
  // Seed 1: -0.003 m/s^2 stated, -0.064 unstated (the lap's mean w^2 times 1.5 m), sigma 0.049.
  EXPECT_LT(std::abs(stated.forward_mps2), stated.sigma_mps2);
  EXPECT_LT(unstated.forward_mps2, stated.forward_mps2 - 0.04);
}

TEST(DriveForwardOffset, AnOffsetShiftsTheMeasureByItselfAndIsRemovedBeyondItsSigma) {
  const Log clean = lap("circuit", 0.0);
  const Log pitched = lap("circuit", -0.3);
  const DriveForwardOffset before = measured(clean, DriveSlope::kClosedLoop);
  const DriveForwardOffset after = measured(pitched, DriveSlope::kClosedLoop);
  EXPECT_NEAR(after.forward_mps2 - before.forward_mps2, -0.3, 1e-9);
  EXPECT_NEAR(after.sigma_mps2, before.sigma_mps2, 1e-9);  // the white noise's is the same
  EXPECT_TRUE(after.removed);
  EXPECT_EQ(after.left_sigma_mps2(), after.sigma_mps2);
  EXPECT_NEAR(before.left_sigma_mps2(), std::hypot(before.forward_mps2, before.sigma_mps2), 1e-15);
}

TEST(DriveForwardOffset, AnImuGapSplitsTheDriveAndEachStretchCountsItsOwnSpeedGain) {
  const Log whole = lap("circuit", 0.2);
  Log gapped = whole;
  ImuStream& imu = *gapped.imu;
  // 20 s taken out in full acceleration: without the split the gap's speed gain would be read
  // as offset.
  const auto from = std::lower_bound(imu.t_s.begin(), imu.t_s.end(), 100.0) - imu.t_s.begin();
  const auto to = std::lower_bound(imu.t_s.begin(), imu.t_s.end(), 120.0) - imu.t_s.begin();
  for (auto* column : {&imu.t_s, &imu.ax_mps2, &imu.ay_mps2, &imu.wz_radps})
    column->erase(column->begin() + from, column->begin() + to);
  const DriveForwardOffset full = measured(whole, DriveSlope::kClosedLoop);
  const DriveForwardOffset split = measured(gapped, DriveSlope::kClosedLoop);
  EXPECT_NEAR(split.duration_s, full.duration_s - 20.0, 0.1);
  EXPECT_NEAR(split.forward_mps2, 0.2, split.sigma_mps2);
  EXPECT_NEAR(split.forward_mps2, full.forward_mps2, 0.2 * full.sigma_mps2);
}

// A stretch whose first samples have no speed starts at the first that has one. The lap cut at
// 0.9 s lost its only stretch (no note for a 0.7 m/s^2 offset in `odocal doctor`): the speed's
// window behind the first IMU sample, 0.9 + 0.5 - 0.5 s, ended a rounding before the wheels'
// first sample. A chain break at 1 s likewise.
TEST(DriveForwardOffset, AStretchWhoseStartHasNoSpeedStartsWhereItHasOne) {
  const Log whole = lap("circuit", -0.7, 2);
  const Log cut = slice_log(whole, 0.9, kWhole);
  const DriveForwardOffset from_cut = measured(cut, DriveSlope::kClosedLoop);
  EXPECT_NEAR(from_cut.forward_mps2, -0.7, 3.0 * from_cut.sigma_mps2);
  EXPECT_GT(from_cut.duration_s, whole.imu->t_s.back() - 3.0);
  Log broken = whole;
  broken.wheels.chain_break.assign(broken.wheels.size(), 0);
  const auto at_1s = std::lower_bound(broken.wheels.t_s.begin(), broken.wheels.t_s.end(), 1.0);
  broken.wheels.chain_break[static_cast<std::size_t>(at_1s - broken.wheels.t_s.begin())] = 1;
  const DriveForwardOffset after_break = measured(broken, DriveSlope::kClosedLoop);
  EXPECT_NEAR(after_break.forward_mps2, -0.7, 3.0 * after_break.sigma_mps2);
  EXPECT_GT(after_break.duration_s, whole.imu->t_s.back() - 3.0);
}

TEST(DriveForwardOffset, WithoutTheSlopeOrEnoughDrivingItSaysNothing) {
  const Log log = lap("circuit", 0.0);
  const DriveForwardSums sums =
      drive_forward_sums(log, log.vehicle.nominal_params(), -kWhole, kWhole);
  EXPECT_FALSE(drive_forward_offset(sums, log.vehicle.body_geometry(), std::nullopt));
  const DriveForwardSums short_drive =
      drive_forward_sums(log, log.vehicle.nominal_params(), 40.0, 65.0);
  EXPECT_FALSE(
      drive_forward_offset(short_drive, log.vehicle.body_geometry(), DriveSlope::kClosedLoop));
  Log no_imu = log;
  no_imu.imu.reset();
  EXPECT_EQ(drive_forward_sums(no_imu, log.vehicle.nominal_params(), -kWhole, kWhole).duration_s,
            0.0);
}

TEST(DriveForwardOffset, WherePreparedALogWithTooFewStopsHasItRemovedAndReported) {
  // A lap of the circuit, which stops once at its end: the drive measures the offset, which the
  // preparation takes out of ax.
  CalibrationOptions no_stops;
  const Log log = lap("circuit", -0.7);
  LogPreparation done;
  const std::optional<Log> prepared = prepare_log(log, no_stops, done);
  ASSERT_TRUE(prepared.has_value()) << done.describe();
  ASSERT_TRUE(done.drive_forward_offset.has_value()) << done.describe();
  const DriveForwardOffset& offset = *done.drive_forward_offset;
  EXPECT_TRUE(offset.removed);
  EXPECT_NEAR(offset.forward_mps2, -0.7, 3.0 * offset.sigma_mps2);
  EXPECT_LT(offset.sigma_mps2, 0.06);
  EXPECT_EQ(done.unevenly_removed_forward_mps2, 0.0);  // one block
  EXPECT_NE(done.describe().find("accelerometer's forward offset removed over"), std::string::npos)
      << done.describe();
  testing::expect_forward_offset_removed(*log.imu, *prepared->imu, offset.forward_mps2);

  // One fix 400 m off at either end neither opens the loop nor closes an open one.
  Log outliers = log;
  outliers.gnss.x_m.front() += 400.0;
  outliers.gnss.y_m.back() -= 400.0;
  LogPreparation despite;
  prepare_log(outliers, no_stops, despite);
  ASSERT_TRUE(despite.drive_forward_offset.has_value()) << despite.describe();
  EXPECT_EQ(despite.drive_forward_offset->forward_mps2, offset.forward_mps2);

  // Cut open (the first half of the lap, no altitude): the slope is not known, nothing removed.
  LogPreparation open;
  const double half_s = 0.5 * (log.wheels.t_s.front() + log.wheels.t_s.back());
  prepare_log(slice_log(log, log.wheels.t_s.front(), half_s), no_stops, open);
  EXPECT_FALSE(open.drive_forward_offset.has_value()) << open.describe();
}

TEST(DriveForwardOffset, OnRampsWithAltitudeTheGradesGravityIsOutAndTheOpenDriveMeasuresIt) {
  // The parking drive climbs its ramps and ends away from its start: with the GNSS altitude the
  // preparation projects the grade (its gravity out of ax), and the drive measures the offset.
  sim::Scenario scenario = load_scenario("parking");
  scenario.gnss.altitude = sim::GnssSimConfig::Altitude::kAlways;
  Log log = simulated_log(sim::simulate(scenario));
  ASSERT_FALSE(log.gnss.altitude_m.empty());
  for (double& ax : log.imu->ax_mps2) ax -= 0.3;
  CalibrationOptions no_stops;
  no_stops.standstill.min_duration_s = 600.0;
  LogPreparation done;
  prepare_log(log, no_stops, done);
  ASSERT_TRUE(done.typical_max_grade.has_value());
  ASSERT_TRUE(done.drive_forward_offset.has_value()) << done.describe();
  EXPECT_NEAR(done.drive_forward_offset->forward_mps2, -0.3, done.drive_forward_offset->sigma_mps2);
  EXPECT_TRUE(done.drive_forward_offset->removed);
  // Without the altitude the open drive cannot tell the ramps from the offset.
  log.gnss.altitude_m.clear();
  LogPreparation flat;
  prepare_log(log, no_stops, flat);
  EXPECT_FALSE(flat.drive_forward_offset.has_value()) << flat.describe();
}

TEST(DriveForwardOffset, BlocksThatRemovedAnotherEstimateThanTheDriveSaysArePreparedAgain) {
  // The lap prepared in blocks of 60 s, as a long log is: it closes only in its last block, so
  // a single pass's blocks before it knew no slope and left the 0.2 m/s^2 in (their one stop's
  // reading at the unmeasured sigma of 0.1 could not remove it), while the last removed what the
  // whole drive says. What they removed differs by 0.2 m/s^2 over two thirds of the time.
  const Log log = lap("circuit", -0.2);
  CalibrationOptions blocks;
  blocks.prepare_block_s = 60.0;
  LogPreparation single;
  InMemoryLogSource source(log);
  BlockPreparation one_pass(source, blocks, single);
  while (one_pass.next()) {
  }
  ASSERT_TRUE(single.drive_forward_offset.has_value()) << single.describe();
  EXPECT_GT(single.unevenly_removed_forward_mps2, 0.1);
  EXPECT_LT(single.unevenly_removed_forward_mps2, 0.2);
  EXPECT_NE(single.describe().find("each removed the estimate of their time"), std::string::npos)
      << single.describe();
  InMemoryLogSource again(log);
  EXPECT_EQ(whole_log_forward_offset(again, blocks), single.removed_forward_mps2);

  // prepare_log prepares it again with the last block's estimate removed from every block.
  LogPreparation done;
  const std::optional<Log> prepared = prepare_log(log, blocks, done);
  ASSERT_TRUE(prepared.has_value());
  ASSERT_TRUE(done.drive_forward_offset.has_value()) << done.describe();
  EXPECT_TRUE(done.drive_forward_offset->removed);
  EXPECT_NEAR(done.drive_forward_offset->forward_mps2, -0.2,
              3.0 * done.drive_forward_offset->sigma_mps2);
  EXPECT_EQ(done.removed_forward_mps2, single.removed_forward_mps2);
  EXPECT_EQ(done.unevenly_removed_forward_mps2, 0.0);
  EXPECT_EQ(done.describe().find("each removed the estimate of their time"), std::string::npos)
      << done.describe();
  testing::expect_forward_offset_removed(*log.imu, *prepared->imu, done.removed_forward_mps2);
  // In one block the same lap removes the same; the blocks' sums (split at their borders) add up
  // to the same measure.
  LogPreparation whole;
  prepare_log(log, CalibrationOptions{}, whole);
  EXPECT_EQ(whole.unevenly_removed_forward_mps2, 0.0);
  EXPECT_NEAR(whole.drive_forward_offset->forward_mps2, done.drive_forward_offset->forward_mps2,
              0.002);
  // Where every block removed the same, there is nothing to prepare again.
  const Log clean = lap("circuit", 0.0);
  InMemoryLogSource clean_source(clean);
  EXPECT_FALSE(whole_log_forward_offset(clean_source, blocks).has_value());
}

}  // namespace
}  // namespace odocal
