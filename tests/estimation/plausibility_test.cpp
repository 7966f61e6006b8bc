// No confident wrong answer: an estimate that makes no physical sense is not a usable result,
// and its message names the likely input mistake.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

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
