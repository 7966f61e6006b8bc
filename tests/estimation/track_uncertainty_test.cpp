// The held track's share of the plain fit's sigma (track_width_uncertainty,
// docs/batch-calibration.md, "The track the wheels roll on").

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "../support/plain_bias_covered.hpp"
#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/estimation/iterative_calibration.hpp"
#include "odocal/io/calibration_io.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

sim::SimulatedDrive parking_drive(double gauss_markov_sigma_m) {
  sim::Scenario scenario = load_scenario("parking");
  scenario.vehicle.wear_rl_mm = 1.5;
  scenario.vehicle.wear_rr_mm = 1.0;
  scenario.seeds.noise = 1;
  if (gauss_markov_sigma_m > 0.0) {
    scenario.gnss.sigma_m = 0.05;
    scenario.gnss.gauss_markov_sigma_m = gauss_markov_sigma_m;
    scenario.gnss.gauss_markov_tau_s = 30.0;
  }
  return sim::simulate(scenario);
}

BatchOptions plain_options() {
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kNone;
  options.max_sigma_circumference_m = 0.05;  // score every estimate
  return options;
}

// The realistic parking drive under a correlated GNSS error, stated as it is: the GNSS fixes
// hardly pin its 585 m, so the turns set the scale through the track, and the load transfer in
// its tight turns moves the track the wheels roll on. Taken as exact, the plain fit is 8.4 mm off
// at a sigma of 1.8 mm; with 1 % of the track, its sigma is 12 mm.
TEST(TrackUncertainty, CoversThePlainFitOfTightTurnsThatGnssDoesNotPin) {
  const sim::SimulatedDrive drive = parking_drive(0.5);
  const Log log = simulated_log(drive);
  BatchOptions options = plain_options();
  options.gnss_gauss_markov_sigma_m = 0.5;
  options.gnss_gauss_markov_tau_s = 30.0;
  testing::expect_the_track_held_covers_the_plain_bias(log, options,
                                                       drive.true_params.circumference_rl_m);
  // Judged, the model does not explain the log (the load transfer): the track is not put under
  // its prior, which would let it take the turns' misfit (track_prior_test.cpp).
  const BatchSummary judged = calibrate_batch(log, options);
  EXPECT_FALSE(judged.model_adequacy.explains) << judged.full_report();
  EXPECT_FALSE(judged.track_under_prior) << judged.full_report();
}

TEST(TrackUncertainty, ItsShareIsLinearInTheUncertaintyAndNoneWhereTheTrackIsFreeOrATyreFitted) {
  const sim::SimulatedDrive drive = parking_drive(0.0);
  const Log log = simulated_log(drive);
  const CalibrationOptions unjudged = testing::unjudged_options();
  BatchOptions options = plain_options();
  const BatchSummary one = calibrate_batch(log, options, unjudged);
  ASSERT_GT(one.track_sigma_m[0], 1e-3) << one.full_report();
  options.track_width_uncertainty = 0.02;
  const BatchSummary two = calibrate_batch(log, options, unjudged);
  EXPECT_EQ(two.estimate.circumference_rl_m, one.estimate.circumference_rl_m);
  for (std::size_t w = 0; w < 2; ++w)
    EXPECT_NEAR(two.track_sigma_m[w], 2.0 * one.track_sigma_m[w], 0.05 * one.track_sigma_m[w]);
  // In the sigma and the JSON.
  EXPECT_GE(one.sigma_rl_m(), one.track_sigma_m[0]);
  const nlohmann::json json = summary_to_json(one, {});
  EXPECT_DOUBLE_EQ(json.at("track_sigma_m").at(0).get<double>(), one.track_sigma_m[0]);
  EXPECT_DOUBLE_EQ(json.at("track_width_uncertainty").get<double>(), 0.01);
  EXPECT_TRUE(json.at("track_share_worth_naming").get<bool>());
  EXPECT_NE(one.full_report().find("from the track width held"), std::string::npos);

  options.track_width_uncertainty = 0.01;
  options.estimate_track_width = true;
  const BatchSummary free = calibrate_batch(log, options, unjudged);
  EXPECT_EQ(free.track_sigma_m[0], 0.0);
  EXPECT_FALSE(summary_to_json(free, {}).contains("track_sigma_m"));
  options.estimate_track_width = false;
  options.tyre_model = TyreModelChoice::kPhysical;
  const BatchSummary physical = calibrate_batch(log, options, unjudged);
  EXPECT_EQ(physical.track_sigma_m[0], 0.0);
}

// The iterative method holds the track as the plain batch does: its sigma carries the share that
// the judge's plain fit of the same log finds, and its report and JSON name it.
TEST(TrackUncertainty, TheIterativeMethodCarriesTheJudgesShareAndNamesIt) {
  const sim::SimulatedDrive drive = parking_drive(0.0);
  const Log log = simulated_log(drive);
  const IterativeSummary iterative = calibrate_iterative(log);
  ASSERT_TRUE(iterative.usable()) << iterative.full_report();
  ASSERT_GT(iterative.track_sigma_m[0], 1e-3) << iterative.full_report();
  EXPECT_EQ(iterative.track_width_uncertainty, BatchOptions{}.track_width_uncertainty);
  const BatchSummary plain = calibrate_batch(log, plain_options());
  for (std::size_t w = 0; w < 2; ++w)
    EXPECT_NEAR(iterative.track_sigma_m[w], plain.track_sigma_m[w], 0.2 * plain.track_sigma_m[w]);
  EXPECT_GE(iterative.sigma_rl_m(), iterative.track_sigma_m[0]);
  EXPECT_GE(iterative.sigma_rr_m(), iterative.track_sigma_m[1]);
  const double error_m =
      iterative.estimate.circumference_rl_m - drive.true_params.circumference_rl_m;
  EXPECT_LT(std::abs(error_m), 3.0 * iterative.sigma_rl_m()) << iterative.full_report();
  EXPECT_NE(iterative.full_report().find("from the track width held"), std::string::npos)
      << iterative.full_report();
  EXPECT_TRUE(summary_to_json(iterative, {}).at("track_share_worth_naming").get<bool>());
}

}  // namespace
}  // namespace odocal
