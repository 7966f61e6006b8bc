// The doctor's check of wheels.csv's drive_force_n clock: against the accelerometer's forward
// reading (its own delay added back) and, without an IMU, the wheels' acceleration. Simulated
// drives with the column, shifted as a bus logged on another clock would be.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/log_diagnosis.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

Log drive_with_force(const std::string& scenario_name, Drivetrain drivetrain) {
  sim::Scenario scenario = load_scenario(scenario_name);
  scenario.route.laps = 1;
  scenario.dynamics.drivetrain = drivetrain;
  scenario.wheels.drive_force_sigma_n = 100.0;
  return simulated_log(sim::simulate(scenario));
}

// The column `late_s` late: each row holds the force of late_s before.
Log with_force_late(Log log, double late_s) {
  const std::vector<double> t = log.wheels.t_s, force = log.wheels.drive_force_n;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double at = std::clamp(t[k] - late_s, t.front(), t.back());
    log.wheels.drive_force_n[k] = *interpolate_linear(t, force, at);
  }
  return log;
}

// A copy: the diagnoses are temporaries.
std::optional<Finding> force_clock_finding(const Diagnosis& diagnosis) {
  for (const Finding& f : diagnosis.findings)
    if (f.check == "time.drive_force_offset") return f;
  return std::nullopt;
}

TEST(DoctorDriveForceClock, AForceOnAnotherClockIsNamedWithItsOffset) {
  const Log log = drive_with_force("urban", Drivetrain::kRear);
  EXPECT_FALSE(force_clock_finding(diagnose_log(log)));
  const Diagnosis late = diagnose_log(with_force_late(log, 0.3));
  const std::optional<Finding> blocking = force_clock_finding(late);
  ASSERT_TRUE(blocking);
  EXPECT_EQ(blocking->severity, FindingSeverity::kBlocking);
  EXPECT_NEAR(blocking->estimate, 0.3, 0.04);
  EXPECT_NE(blocking->fix.find("wheels.drive_force"), std::string::npos) << blocking->fix;
  EXPECT_TRUE(late.blocking());
  // 0.1 s early: below what blocks, but the tyre model feels it.
  const std::optional<Finding> warning =
      force_clock_finding(diagnose_log(with_force_late(log, -0.1)));
  ASSERT_TRUE(warning);
  EXPECT_EQ(warning->severity, FindingSeverity::kWarning);
  EXPECT_NEAR(warning->estimate, -0.1, 0.04);
}

// Raced on a rear-driven car, the driven wheels' speed leads their force by their slip's rate:
// the accelerometer, which reads the body, is the clock's judge; without one, only a larger
// offset is named.
TEST(DoctorDriveForceClock, AHardDrivenWheelsSlipIsNoClockOffset) {
  const Log log = drive_with_force("circuit", Drivetrain::kRear);
  EXPECT_FALSE(force_clock_finding(diagnose_log(log)));
  const std::optional<Finding> late = force_clock_finding(diagnose_log(with_force_late(log, 0.2)));
  ASSERT_TRUE(late);
  EXPECT_NEAR(late->estimate, 0.2, 0.03);
  Log without_imu = log;
  without_imu.imu.reset();
  EXPECT_FALSE(force_clock_finding(diagnose_log(without_imu)));
  without_imu = with_force_late(without_imu, 0.5);
  const std::optional<Finding> named = force_clock_finding(diagnose_log(without_imu));
  ASSERT_TRUE(named);
  EXPECT_EQ(named->severity, FindingSeverity::kBlocking);
}

}  // namespace
}  // namespace odocal
