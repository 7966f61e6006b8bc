// The doctor's clock lags: a third signal that leads the second (a car's drive slip in its wheel
// speed) is taken out of the lag, and an antenna behind the axle, which delays only the GNSS
// course, is not read as a clock offset.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "../support/doctor_faults.hpp"
#include "../support/run_cli.hpp"
#include "../support/temp_log_dir.hpp"
#include "estimation/diagnosis_signals.hpp"
#include "odocal/estimation/log_diagnosis.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

using detail::cross_correlation_lag;
using detail::partial_cross_correlation_lag;

// A speed-like signal x and y = x delayed by 0.4 s plus a lead proportional to x times its rate
// (as wheel slip is to speed times acceleration): the plain cross-correlation reads the lead as
// less delay, the partial one given that product reads the 0.4 s.
TEST(DiagnosisLag, ALeadProportionalToAThirdSignalIsTakenOutOfTheLag) {
  constexpr double kStep = 0.1, kDelay = 0.4, kLead = 0.08;
  const auto speed = [](double t) {
    return 8.0 + 5.0 * std::sin(0.21 * t) + 2.0 * std::sin(0.53 * t + 1.0) +
           1.0 * std::sin(1.3 * t + 2.0);
  };
  const auto rate = [](double t) {
    return 5.0 * 0.21 * std::cos(0.21 * t) + 2.0 * 0.53 * std::cos(0.53 * t + 1.0) +
           1.0 * 1.3 * std::cos(1.3 * t + 2.0);
  };
  std::vector<double> x, y, product;
  for (int k = 0; k < 3000; ++k) {
    const double t = k * kStep;
    x.push_back(speed(t));
    product.push_back(speed(t) * rate(t));
    // Delayed, the lead taken at the instant the delayed value belongs to.
    y.push_back(speed(t - kDelay) - kLead * speed(t - kDelay) * rate(t - kDelay));
  }
  const detail::Lag plain = cross_correlation_lag(x, y, kStep, 3.0);
  const detail::Lag partial = partial_cross_correlation_lag(x, y, product, kStep, 3.0);
  EXPECT_GT(std::abs(plain.lag_s - kDelay), 0.1) << plain.lag_s;
  EXPECT_NEAR(partial.lag_s, kDelay, 0.02);
  EXPECT_GT(partial.peak, 0.999);
}

// Without the third signal's part, the partial lag is the plain one.
TEST(DiagnosisLag, AThirdSignalUnrelatedToTheDelayLeavesTheLagAlone) {
  constexpr double kStep = 0.1;
  std::vector<double> x, y, unrelated;
  for (int k = 0; k < 2000; ++k) {
    const double t = k * kStep;
    x.push_back(std::sin(0.3 * t) + 0.5 * std::sin(0.9 * t));
    y.push_back(std::sin(0.3 * (t - 0.7)) + 0.5 * std::sin(0.9 * (t - 0.7)));
    unrelated.push_back(std::cos(2.3 * t + 0.4));
  }
  EXPECT_NEAR(partial_cross_correlation_lag(x, y, unrelated, kStep, 3.0).lag_s, 0.7, 0.01);
  EXPECT_NEAR(cross_correlation_lag(x, y, kStep, 3.0).lag_s, 0.7, 0.01);
}

bool blames_the_gnss_clock(const Diagnosis& diagnosis) {
  for (const Finding& f : diagnosis.findings)
    if (f.check == "time.gnss_offset") return true;
  return false;
}

sim::Scenario urban_with_rtk_fixes(double latency_s) {
  sim::Scenario scenario = load_scenario("urban");
  scenario.seeds.noise = scenario.seeds.trajectory = 33;
  scenario.gnss.sigma_m = 0.02;
  scenario.gnss.latency_s = latency_s;
  return scenario;
}

// The mounting bench's run 33: RTK fixes 107 ms late from an antenna 0.81 m behind the axle. The
// course rate's lag (+0.35 s) was blocked as a GNSS clock offset; the speed, drive slip taken
// out, reads 0.13 s, below the doctor's 0.15 s. The same log with its clock 0.6 s off is blocked.
TEST(DiagnosisLag, AnAntennaBehindTheAxleBesideALatencyIsNoGnssClockOffset) {
  sim::Scenario scenario = urban_with_rtk_fixes(0.107);
  scenario.gnss.lever_arm_x_m = -0.81;
  scenario.gnss.lever_arm_y_m = 0.05;
  EXPECT_FALSE(blames_the_gnss_clock(diagnose_log(simulated_log(sim::simulate(scenario)))));
  scenario.gnss.latency_s = 0.6 + 0.107;
  const Diagnosis late = diagnose_log(simulated_log(sim::simulate(scenario)));
  ASSERT_TRUE(blames_the_gnss_clock(late));
  for (const Finding& f : late.findings) {
    if (f.check == "time.gnss_offset") {
      EXPECT_EQ(f.severity, FindingSeverity::kBlocking);
      EXPECT_GT(f.estimate, 0.5);
    }
  }
}

double gnss_clock_estimate(const Diagnosis& diagnosis) {
  for (const Finding& f : diagnosis.findings)
    if (f.check == "time.gnss_offset" && f.severity == FindingSeverity::kBlocking)
      return f.estimate;
  return std::numeric_limits<double>::quiet_NaN();
}

// The course rate only where the GNSS moves: read as 0 below 2 m/s, it held still through the
// start of each turn from rest and read a 0.6 s clock 0.1 s late on the urban drive (seeds 1-5:
// +0.66 to +0.75 s, mean |error| 0.100 s), and on two of the doctor matrix's parking drives it was
// missed. Read where it moves, the mean |error| is 0.035 s in Release and 0.062 s in the sanitizer
// build (clang at -O1 simulates other rounding, and a seed's peak moves by a lag step).
TEST(DiagnosisLag, AGnssClockIsReadFromTheCourseWhereTheGnssMoves) {
  constexpr double kClockS = 0.6;
  double error_sum = 0.0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    sim::Scenario scenario = load_scenario("urban");
    scenario.seeds.noise = scenario.seeds.trajectory = seed;
    scenario.gnss.latency_s = kClockS;
    const double estimate =
        gnss_clock_estimate(diagnose_log(simulated_log(sim::simulate(scenario))));
    ASSERT_TRUE(std::isfinite(estimate)) << "urban seed " << seed;
    error_sum += std::abs(estimate - kClockS);
  }
  EXPECT_LT(error_sum / 5, 0.08);
  // The doctor matrix's parking drives of seeds 14 and 17, their gnss.csv shifted as there.
  const testing::TempLogDir dir;
  for (unsigned seed : {14u, 17u}) {
    const std::filesystem::path log = dir.path() / fmt::format("parking-{}", seed);
    const testing::CliRun run = testing::run_cli(
        fmt::format("simulate --scenario parking --laps 1 --seed {0} --trajectory-seed {0} {1} "
                    "--out {2}",
                    seed, testing::kCleanLogFlags, log.string()));
    ASSERT_EQ(run.status, 0) << run.err;
    testing::edit_csv(log / "gnss.csv", [&](testing::Row& r) { r["t"] += kClockS; });
    EXPECT_NEAR(gnss_clock_estimate(testing::doctor_directory(log)), kClockS, 0.2)
        << "parking seed " << seed;
  }
}

// An antenna behind the axle makes the course trail by about x / v, which a clock's estimate
// takes on (+0.13 s for 0.81 m on the urban drive; one 1.5 m ahead leads by 0.26 s). Stated in
// vehicle.yaml, it is taken out: the clock reads as with the antenna over the axle.
TEST(DiagnosisLag, AStatedAntennasCourseLagIsTakenOutOfTheGnssClock) {
  constexpr double kClockS = 0.6;
  const auto clock_read = [&](Eigen::Vector2d antenna_m, bool stated) {
    sim::Scenario scenario = urban_with_rtk_fixes(kClockS);
    scenario.gnss.lever_arm_x_m = antenna_m.x();
    scenario.gnss.lever_arm_y_m = antenna_m.y();
    scenario.gnss.lever_arm_stated = stated;
    return gnss_clock_estimate(diagnose_log(simulated_log(sim::simulate(scenario))));
  };
  const double over_the_axle = clock_read({0.0, 0.0}, false);
  ASSERT_TRUE(std::isfinite(over_the_axle));
  for (const Eigen::Vector2d antenna : {Eigen::Vector2d(-0.81, 0.0), Eigen::Vector2d(1.5, 0.4)}) {
    const double unstated = clock_read(antenna, false);
    const double stated = clock_read(antenna, true);
    EXPECT_GT(std::abs(unstated - over_the_axle), 0.1)
        << unstated << " against " << over_the_axle << " at " << antenna.transpose();
    EXPECT_NEAR(stated, over_the_axle, 0.02)
        << "unstated " << unstated << " at " << antenna.transpose();
  }
  // Stated over the axle, nothing changes.
  EXPECT_NEAR(clock_read({0.0, 0.0}, true), over_the_axle, 1e-9);
}

}  // namespace
}  // namespace odocal
