// No confident wrong answer: an estimate that makes no physical sense is not a usable result,
// and its message names the likely input mistake.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "../support/unjudged_options.hpp"
#include "estimation/calibration_run.hpp"
#include "estimation/input_mistake_hint.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

CalibrationSummary converged_summary(double c_rl, double c_rr) {
  CalibrationSummary s;
  s.nominal = {2.0, 2.0, 1.6};
  s.estimate = {c_rl, c_rr, 1.6};
  s.covariance = 1e-8 * Eigen::Matrix2d::Identity();
  s.before = {10.0, 20.0, 0.01, 0.02};
  s.after = {1.0, 2.0, 0.001, 0.002};
  return s;
}

double square(double v) { return v * v; }

Log ticks_log(double ticks_per_rev) {
  Log log;
  log.wheels.unit_rear = WheelUnit::kTicks;
  log.vehicle.ticks_per_rev = ticks_per_rev;
  return log;
}

TEST(Plausibility, AnEstimateNearNominalThatDeadReckonsBetterIsUsable) {
  CalibrationSummary s = converged_summary(2.01, 1.99);
  check_plausibility(Log{}, {}, s);
  EXPECT_TRUE(s.usable()) << s.message;
}

TEST(Plausibility, FarFromNominalIsImplausibleAndNamesTheFactor) {
  CalibrationSummary s = converged_summary(1.0, 1.0);  // half the nominal circumference
  check_plausibility(ticks_log(48), {}, s);
  EXPECT_EQ(s.termination, Termination::kImplausible);
  EXPECT_NE(s.message.find("-50.0 %"), std::string::npos) << s.message;
  EXPECT_NE(s.message.find("ticks_per_rev off by a factor of 2 (vehicle.yaml says 48; try 96)"),
            std::string::npos)
      << s.message;
  EXPECT_NE(s.message.find("diameter given where the radius belongs"), std::string::npos);
}

TEST(Plausibility, NonFiniteOrNegativeEstimatesAreImplausible) {
  CalibrationSummary nan = converged_summary(std::nan(""), 2.0);
  check_plausibility(Log{}, {}, nan);
  EXPECT_EQ(nan.termination, Termination::kImplausible);
  CalibrationSummary negative = converged_summary(-1.96, -1.96);
  check_plausibility(Log{}, {}, negative);
  EXPECT_EQ(negative.termination, Termination::kImplausible);
  EXPECT_NE(negative.message.find("wheel signs look reversed"), std::string::npos)
      << negative.message;
  CalibrationSummary infinite_sigma = converged_summary(2.0, 2.0);
  infinite_sigma.covariance(0, 0) = std::numeric_limits<double>::infinity();
  check_plausibility(Log{}, {}, infinite_sigma);
  EXPECT_EQ(infinite_sigma.termination, Termination::kImplausible);
}

TEST(Plausibility, DeadReckoningWorseThanNominalIsImplausible) {
  CalibrationSummary s = converged_summary(2.01, 2.01);
  s.after = {15.0, 30.0, 0.02, 0.04};  // worse than `before`
  check_plausibility(Log{}, {}, s);
  EXPECT_EQ(s.termination, Termination::kImplausible);
  EXPECT_NE(s.message.find("10.00 m -> 15.00 m"), std::string::npos) << s.message;
  // Within the tolerance and the noise floor it is not.
  CalibrationSummary close = converged_summary(2.0, 2.0);
  close.after = {10.2, 20.0, 0.01, 0.02};
  check_plausibility(Log{}, {}, close);
  EXPECT_TRUE(close.usable()) << close.message;
}

TEST(Plausibility, WorseDeadReckoningWithTheNominalInsideThreeSigmaIsUsableWithANote) {
  CalibrationSummary s = converged_summary(2.0002, 2.0001);
  s.covariance = square(0.0001) * Eigen::Matrix2d::Identity();  // nominal at 2.2 sigma
  s.after = {15.0, 30.0, 0.02, 0.04};
  check_plausibility(Log{}, {}, s);
  EXPECT_TRUE(s.usable()) << s.message;
  EXPECT_NE(s.note.find("inside this estimate's 3-sigma region (Mahalanobis distance 2.2)"),
            std::string::npos)
      << s.note;
  EXPECT_NE(s.note.find("keep the nominal ones"), std::string::npos) << s.note;

  CalibrationSummary outside = s;
  outside.termination = Termination::kConverged;
  outside.note.clear();
  outside.estimate = {2.0004, 2.0001, 1.6};  // 4.1 sigma
  check_plausibility(Log{}, {}, outside);
  EXPECT_EQ(outside.termination, Termination::kImplausible);
  EXPECT_TRUE(outside.note.empty());
}

TEST(Plausibility, ACommonScaleOnlyEstimateIsJudgedAlongItsOneDirection) {
  // Only the common scale was estimated: the covariance has rank one along the nominal ratio.
  const Eigen::Vector2d along = Eigen::Vector2d(1.0, 1.0).normalized();
  CalibrationSummary scale = converged_summary(2.0001, 2.0001);
  scale.covariance = square(0.0001) * along * along.transpose();
  scale.after = {15.0, 30.0, 0.02, 0.04};
  check_plausibility(Log{}, {}, scale);
  EXPECT_TRUE(scale.usable()) << scale.message;
  EXPECT_FALSE(scale.note.empty());
  // A difference the covariance says cannot occur is no sampling error.
  CalibrationSummary across = scale;
  across.note.clear();
  across.estimate = {2.0001, 1.9999, 1.6};
  check_plausibility(Log{}, {}, across);
  EXPECT_EQ(across.termination, Termination::kImplausible);
}

TEST(Plausibility, HintsForKnownFactors) {
  EXPECT_NE(likely_input_mistake(2.0 * M_PI, Log{}).find("radians read as revolutions"),
            std::string::npos);
  EXPECT_NE(likely_input_mistake(1.0 / 3.6, Log{}).find("km/h read as m/s"), std::string::npos);
  EXPECT_NE(likely_input_mistake(0.001, Log{}).find("ms read as s"), std::string::npos);
  EXPECT_NE(likely_input_mistake(1.2, Log{}).find("1.2 times the nominal value"),
            std::string::npos);
}

struct Drive {
  Log log;
  OdometryParams truth;
};

Drive one_lap() {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  scenario.route.laps = 1;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  return {simulated_log(drive), drive.true_params};
}

TEST(Plausibility, ReversedEncodersGiveNoResult) {
  Drive drive = one_lap();
  for (double& n : drive.log.wheels.rev_rl) n = -n;
  for (double& n : drive.log.wheels.rev_rr) n = -n;
  const IterativeSummary iterative = calibrate_iterative(drive.log);
  EXPECT_FALSE(iterative.usable());
  EXPECT_EQ(iterative.termination, Termination::kImplausible) << iterative.message;
  const AugmentedSummary augmented = calibrate_augmented(drive.log);
  EXPECT_FALSE(augmented.usable()) << augmented.brief_report();
}

// The simulator's unworn car over 3 laps (13.6 km): every estimate is a fraction of a millimetre
// off the nominal, within its sigma, which is metres of dead reckoning: no refusal.
TEST(Plausibility, AnUnwornCarIsNoInputMistake) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  ASSERT_EQ(scenario.vehicle.wear_rl_mm, 0.0);
  ASSERT_EQ(scenario.vehicle.wear_rr_mm, 0.0);
  const Log log = simulated_log(drive);
  const IterativeSummary iterative = calibrate_iterative(log, {}, testing::unjudged_options());
  EXPECT_TRUE(iterative.usable()) << iterative.message;
  const BatchSummary batch = calibrate_batch(log);
  EXPECT_TRUE(batch.usable()) << batch.message;
}

TEST(Plausibility, ATicksPerRevOffByTwoIsNamed) {
  Drive drive = one_lap();
  for (double& n : drive.log.wheels.rev_rl) n *= 2.0;  // what ticks_per_rev 48 instead of 96 does
  for (double& n : drive.log.wheels.rev_rr) n *= 2.0;
  drive.log.vehicle.ticks_per_rev = 48;
  const IterativeSummary result = calibrate_iterative(drive.log);
  EXPECT_EQ(result.termination, Termination::kImplausible);
  EXPECT_NE(result.message.find("try 96"), std::string::npos) << result.message;
}

}  // namespace
}  // namespace odocal
