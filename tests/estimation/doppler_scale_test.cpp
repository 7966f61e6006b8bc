// The Doppler column's scale is judged against the wheels before the batch fits it: a column in
// another unit is an input error named with its likely unit, not a fit that ends rank-deficient
// for a reason ("too short") that is not the one.

#include "estimation/doppler_scale.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "odocal/error.hpp"
#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/estimation/reference_filter.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

Log urban_with_doppler(double scale) {
  sim::Scenario scenario = load_scenario("urban");
  scenario.gnss.speed_sigma_mps = 0.05;
  Log log = simulated_log(sim::simulate(scenario));
  for (double& v : log.gnss.speed_mps) v *= scale;
  return log;
}

TEST(DopplerScale, NamesTheUnitsItsRatioMatches) {
  EXPECT_EQ(likely_speed_unit(3.6), "the speed is in km/h (x3.6)");
  EXPECT_EQ(likely_speed_unit(3.5), "the speed is in km/h (x3.6)");  // within 5 %
  EXPECT_NE(likely_speed_unit(2.24).find("mph"), std::string::npos);
  EXPECT_NE(likely_speed_unit(1.94).find("knots"), std::string::npos);
  EXPECT_NE(likely_speed_unit(99.0).find("cm/s"), std::string::npos);
  EXPECT_NE(likely_speed_unit(1010.0).find("mm/s"), std::string::npos);
  EXPECT_EQ(likely_speed_unit(1.0), "");
  EXPECT_EQ(likely_speed_unit(3.0), "");
}

TEST(DopplerScale, TheSimulatorsTrueSpeedMatchesTheWheelsAndAScaledOneDoesNot) {
  const Log clean = urban_with_doppler(1.0);
  const OdometryParams nominal = clean.vehicle.nominal_params();
  const auto ratio = doppler_over_wheels(clean, nominal);
  ASSERT_TRUE(ratio.has_value());
  // The nominal circumferences are within a per cent of the worn, slipping ones.
  EXPECT_NEAR(ratio->ratio, 1.0, 0.01);
  EXPECT_GT(ratio->compared_s, 100.0);
  const auto positions = doppler_over_positions(clean, nominal);
  ASSERT_TRUE(positions.has_value());
  EXPECT_NEAR(positions->ratio, 1.0, 0.03);  // the chords' noise and the turns they cut
  EXPECT_NO_THROW(check_doppler_scale(clean, nominal));
  // A scale is judged whichever way it goes: the driving compared is the wheels', not the column's.
  for (const double scale : {3.6, 1.0 / 3.6, 1.2}) {
    const Log scaled = urban_with_doppler(scale);
    const auto scaled_ratio = doppler_over_wheels(scaled, nominal);
    ASSERT_TRUE(scaled_ratio.has_value());
    EXPECT_NEAR(scaled_ratio->ratio / ratio->ratio, scale, 1e-9 * scale);
    EXPECT_THROW(check_doppler_scale(scaled, nominal), InputError) << scale;
  }
  EXPECT_NO_THROW(check_doppler_scale(urban_with_doppler(1.05), nominal));
  // No column: nothing to judge.
  Log without = clean;
  without.gnss.speed_mps.clear();
  EXPECT_FALSE(doppler_over_wheels(without, nominal).has_value());
}

TEST(DopplerScale, AColumnThatAgreesWithThePositionsIsTheWheelsProblem) {
  // Wheels counted at twice their revolutions: the column is off from them, not from the
  // positions, and the wheels' own checks (the plausibility's likely cause) are the ones to say so.
  Log log = urban_with_doppler(1.0);
  for (auto* column : {&log.wheels.rev_rl, &log.wheels.rev_rr})
    for (double& n : *column) n *= 2.0;
  const OdometryParams nominal = log.vehicle.nominal_params();
  const auto wheels = doppler_over_wheels(log, nominal);
  const auto positions = doppler_over_positions(log, nominal);
  ASSERT_TRUE(wheels && positions);
  EXPECT_NEAR(wheels->ratio, 0.5, 0.01);
  // The doubled wheels let the slow turns in, whose chords cut the path most (1.034 measured).
  EXPECT_NEAR(positions->ratio, 1.0, 0.05);
  EXPECT_NO_THROW(check_doppler_scale(log, nominal));
}

TEST(DopplerScale, CalibrationRefusesAColumnInKilometresPerHourBeforeItReadsIt) {
  const Log log = urban_with_doppler(3.6);
  const auto expect_refused = [&](const BatchOptions& options, const CalibrationOptions& common) {
    try {
      calibrate_batch(log, options, common);
      ADD_FAILURE() << "a Doppler column in km/h was read";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(e.location().field, "speed_mps");
      EXPECT_NE(what.find("gnss.csv"), std::string::npos) << what;
      EXPECT_NE(what.find("km/h"), std::string::npos) << what;
    }
  };
  // The layer-1 reference's speed update (on by default) reads it, for every method and for
  // validate's reference.
  expect_refused(BatchOptions{}, CalibrationOptions{});
  EXPECT_THROW(compute_reference(log, ReferenceOptions{}), InputError);
  // The batch's Doppler fit reads it where the reference does not: by default, or when asked.
  CalibrationOptions no_speed_update;
  no_speed_update.reference.use_gnss_speed = false;
  expect_refused(BatchOptions{}, no_speed_update);
  BatchOptions doppler_fit;
  doppler_fit.gnss_speed_sigma_mps = 0.1;
  expect_refused(doppler_fit, no_speed_update);
  // Where nothing reads the column, the log calibrates: to an answer, refused or not (this
  // rear-driven car's circumferences at rest are not identified to 1 mm without the Doppler
  // speed, and the plain model's carry their gap to the tyre model's).
  BatchOptions no_doppler_fit;
  no_doppler_fit.gnss_speed_sigma_mps = 0.0;
  no_doppler_fit.tyre_model = TyreModelChoice::kNone;
  const BatchSummary s = calibrate_batch(log, no_doppler_fit, no_speed_update);
  EXPECT_TRUE(s.usable() || s.termination == Termination::kNotIdentifiable) << s.full_report();
  EXPECT_TRUE(std::isfinite(s.sigma_rl_m())) << s.full_report();
}

}  // namespace
}  // namespace odocal
