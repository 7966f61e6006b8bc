// Hills: the simulator's wheels roll the 3-D path and its accelerometer feels the slope; the
// grade fitted from GNSS altitude projects the wheels back to the horizontal, so that a hilly
// drive calibrates like a flat one.

#include "odocal/estimation/road_grade.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "experiments/worn_circuit.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

sim::Scenario circuit(double max_grade, int laps) {
  sim::Scenario scenario = experiments::worn_ideal_circuit(laps, 1);
  scenario.route.terrain.max_grade = max_grade;
  return scenario;
}

TEST(RoadGrade, SimulatedWheelsRollTheLongerThreeDimensionalPath) {
  const sim::SimulatedDrive flat = sim::simulate(circuit(0.0, 1));
  const sim::SimulatedDrive hill = sim::simulate(circuit(0.06, 1));
  ASSERT_EQ(hill.gnss_alt.size(), hill.gnss_t_s.size());
  EXPECT_TRUE(flat.gnss_alt.empty());
  const Log flat_log = simulated_log(flat), hill_log = simulated_log(hill);
  double flat_rev = 0.0, hill_rev = 0.0;
  for (std::size_t k = 1; k < flat_log.wheels.size(); ++k) flat_rev += flat_log.wheels.rev_rl[k];
  for (std::size_t k = 1; k < hill_log.wheels.size(); ++k) hill_rev += hill_log.wheels.rev_rl[k];
  // A sinusoidal grade of amplitude g makes the path longer by g^2 / 4 on average.
  EXPECT_NEAR(hill_rev / flat_rev - 1.0, 0.06 * 0.06 / 4.0, 2e-4);
}

TEST(RoadGrade, FittedFromGnssAltitude) {
  const Log log = simulated_log(sim::simulate(circuit(0.06, 1)));
  const auto profile = grade_from_gnss_altitude(log, log.vehicle.nominal_params(), 100.0);
  ASSERT_TRUE(profile.has_value());
  EXPECT_NEAR(profile->typical_max_grade(), 0.06, 0.012);
  EXPECT_NEAR(profile->length_excess(), 0.06 * 0.06 / 4.0, 2.5e-4);
  const Log flat = simulated_log(sim::simulate(circuit(0.0, 1)));
  EXPECT_FALSE(grade_from_gnss_altitude(flat, flat.vehicle.nominal_params(), 100.0).has_value());
}

TEST(RoadGrade, TheProjectionKeepsTheGradeBesideTheWheels) {
  // The grade at each wheel sample against the road's own (a sine of amplitude 0.06 over the
  // distance, so its mean square is 0.0018): what the verdict and the tyre force read later.
  Log log = simulated_log(sim::simulate(circuit(0.06, 1)));
  const auto profile = grade_from_gnss_altitude(log, log.vehicle.nominal_params(), 100.0);
  ASSERT_TRUE(profile.has_value());
  EXPECT_TRUE(log.wheels.grade.empty());
  project_to_horizontal(log, *profile);
  ASSERT_EQ(log.wheels.grade.size(), log.wheels.size());
  double sum_squares = 0.0, distance_m = 0.0;
  for (std::size_t k = 1; k < log.wheels.size(); ++k) {
    const double step_m =
        std::abs(body_increment(log.wheels.increment(k), log.vehicle.nominal_params()).distance_m);
    sum_squares += step_m * log.wheels.grade[k] * log.wheels.grade[k];
    distance_m += step_m;
  }
  EXPECT_NEAR(sum_squares / distance_m, 0.5 * 0.06 * 0.06, 2e-4);
}

TEST(RoadGrade, AHillyDriveCalibratesLikeAFlatOne) {
  const sim::SimulatedDrive hill = sim::simulate(circuit(0.06, 2));
  const Log log = simulated_log(hill);
  const BatchSummary result = calibrate_batch(log);
  CalibrationOptions planar;
  planar.use_gnss_altitude = false;
  const BatchSummary without = calibrate_batch(log, {}, planar);
  const double error = result.estimate.circumference_rl_m - hill.true_params.circumference_rl_m;
  const double error_without =
      without.estimate.circumference_rl_m - hill.true_params.circumference_rl_m;
  SCOPED_TRACE(result.full_report());
  EXPECT_LT(std::abs(error), 3.0 * result.sigma_rl_m());
  EXPECT_GT(std::abs(error_without), 3.0 * std::abs(error));
  EXPECT_NE(result.full_report().find("grade from GNSS altitude within"), std::string::npos);
}

}  // namespace
}  // namespace odocal
