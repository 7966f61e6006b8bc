// Model adequacy on simulated logs, through the batch: the ideal vehicle is explained; a vehicle
// whose wheels turn on a wider track than vehicle.yaml states is not (its heading residual
// follows curvature), until the batch estimates the track; rear wheels that slip climbing hills
// are named by the grade. The other methods are judged on a batch fit of the same model, and say
// the same.

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "../support/hilly_urban.hpp"
#include "../support/test_scenarios.hpp"
#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/estimation/iterative_calibration.hpp"
#include "odocal/io/calibration_io.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

sim::SimulatedDrive ideal_lap(double effective_track_m) {
  return sim::simulate(testing::ideal_lap_on_track(effective_track_m));
}

TEST(ModelAdequacyBatch, IdealVehicleIsExplainedAWrongTrackIsNot) {
  const Log ideal = simulated_log(ideal_lap(0.0));
  EXPECT_TRUE(calibrate_batch(ideal).model_adequacy.explains)
      << calibrate_batch(ideal).model_adequacy.verdict;
  const Log wide = simulated_log(ideal_lap(1.76));  // wheels 10 % further apart than stated
  BatchOptions plain;
  plain.tyre_model = TyreModelChoice::kNone;
  const BatchSummary held = calibrate_batch(wide, plain);
  const ModelAdequacy& fixed_track = held.model_adequacy;
  EXPECT_FALSE(fixed_track.explains);
  EXPECT_FALSE(held.track_under_prior);  // a prior would hide the wrong track
  EXPECT_NE(fixed_track.verdict.find("heading residual follows curvature"), std::string::npos)
      << fixed_track.verdict;
  BatchOptions with_track;
  with_track.estimate_track_width = true;
  EXPECT_TRUE(calibrate_batch(wide, with_track).model_adequacy.explains);
  // auto frees the track itself there
  // (TyreModelBatch.AutoDoesNotTakeATrackThatVehicleYamlGetsWrongForTyres).
  const BatchSummary chosen = calibrate_batch(wide);
  EXPECT_TRUE(chosen.tyre_selection.plain_track_free);
  EXPECT_FALSE(chosen.track_under_prior);
  EXPECT_TRUE(chosen.model_adequacy.explains) << chosen.model_adequacy.verdict;
}

// Hills of up to 6 % on the realistic urban drive: driven from the rear, the wheels slip with
// the climbing force and the verdict names the grade; the free-rolling rear wheels of a
// front-driven car do not climb, and the grade is not what their residual follows.
TEST(ModelAdequacyBatch, RearWheelsThatClimbAreNamedByTheGrade) {
  const auto drive = [](sim::Drivetrain drivetrain) {
    return simulated_log(sim::simulate(testing::hilly_urban(drivetrain)));
  };
  BatchOptions plain;
  plain.tyre_model = TyreModelChoice::kNone;
  const Log rear_log = drive(sim::Drivetrain::kRear);
  const ModelAdequacy rear = calibrate_batch(rear_log, plain).model_adequacy;
  EXPECT_FALSE(rear.explains);
  EXPECT_NE(rear.verdict.find("along-track residual follows grade"), std::string::npos)
      << rear.verdict;
  // By default (auto) the physical terms take the climbing force's slip, and the log is explained.
  const BatchSummary chosen = calibrate_batch(rear_log);
  EXPECT_EQ(chosen.tyre_selection.chosen, "physical");
  EXPECT_TRUE(chosen.model_adequacy.explains) << chosen.model_adequacy.verdict;
  const ModelAdequacy front = calibrate_batch(drive(sim::Drivetrain::kFront), plain).model_adequacy;
  ASSERT_EQ(front.dependences.size(), 5u);
  EXPECT_EQ(front.dependences.back().quantity, "grade");
  EXPECT_LT(std::abs(front.dependences.back().correlation), 0.3);
}

// The realistic urban drive of a rear-driven car with a receiver's Doppler speed: the plain fit's
// along-track residual keeps only a sliver of the drive slip (the poses follow the wheels between
// fixes), the Doppler speed sees it in every interval. The ideal car's is white.
TEST(ModelAdequacyBatch, TheDopplerSpeedNamesTheSlipOfADrivenWheel) {
  sim::Scenario scenario = load_scenario("urban");
  scenario.gnss.speed_sigma_mps = 0.05;
  BatchOptions plain;
  plain.tyre_model = TyreModelChoice::kNone;
  const ModelAdequacy slipping =
      calibrate_batch(simulated_log(sim::simulate(scenario)), plain).model_adequacy;
  EXPECT_FALSE(slipping.explains);
  EXPECT_NE(slipping.verdict.find("Doppler speed residual follows longitudinal acceleration"),
            std::string::npos)
      << slipping.verdict;
  EXPECT_NE(slipping.verdict.find("tyre_model: physical"), std::string::npos) << slipping.verdict;
  scenario.ideal = true;
  const ModelAdequacy rolling =
      calibrate_batch(simulated_log(sim::simulate(scenario)), plain).model_adequacy;
  EXPECT_EQ(rolling.dependences.size(), 6u);
  EXPECT_TRUE(rolling.explains) << rolling.verdict;
}

TEST(ModelAdequacyBatch, EveryMethodIsJudgedUnlessAskedNotTo) {
  const Log ideal = simulated_log(ideal_lap(0.0));
  const Log wide = simulated_log(ideal_lap(1.76));
  for (const CalibrationMethod method :
       {CalibrationMethod::kIterative, CalibrationMethod::kFixedP, CalibrationMethod::kAugmented}) {
    SCOPED_TRACE(method_name(method));
    CalibrationConfig config;
    config.method = method;
    const AnyCalibrationSummary explained = calibrate(ideal, config);
    ASSERT_TRUE(core(explained).usable()) << core(explained).message;
    EXPECT_TRUE(core(explained).model_adequacy.explains) << core(explained).model_adequacy.verdict;
    EXPECT_NE(full_report(explained).find("model        the two-wheel model explains this log"),
              std::string::npos)
        << full_report(explained);
    // Explained or not, a constant per wheel is what this drive rolled on, not the tyre at rest.
    EXPECT_NE(full_report(explained).find("rolling      the circumferences this drive rolled on"),
              std::string::npos)
        << full_report(explained);

    const AnyCalibrationSummary wrong_track = calibrate(wide, config);
    ASSERT_TRUE(core(wrong_track).usable()) << core(wrong_track).message;
    const ModelAdequacy& m = core(wrong_track).model_adequacy;
    EXPECT_FALSE(m.explains);
    EXPECT_NE(m.verdict.find("heading residual follows curvature"), std::string::npos) << m.verdict;
    EXPECT_NE(m.verdict.find("[judged on a batch fit of this log]"), std::string::npos)
        << m.verdict;
    const nlohmann::json json = summary_to_json(wrong_track, config);
    EXPECT_TRUE(json.at("model_adequacy").at("judged").get<bool>());
    EXPECT_FALSE(json.at("model_adequacy").at("explains").get<bool>());
    EXPECT_EQ(json.at("model_adequacy").at("dependences").size(), 4u);

    config.common.judge_model_adequacy = false;
    const AnyCalibrationSummary unjudged = calibrate(wide, config);
    EXPECT_TRUE(core(unjudged).model_adequacy.verdict.empty());
    EXPECT_FALSE(summary_to_json(unjudged, config).contains("model_adequacy"));
    EXPECT_EQ(full_report(unjudged).find("model "), std::string::npos);
  }
  // The wrong track is geometry, not tyres: the tyre models judge with the track width free, and
  // do not move a plain fit (held at the stated track, the load terms took it for load transfer
  // and put the circumferences at rest 43 mm off).
  BatchOptions plain;
  plain.tyre_model = TyreModelChoice::kNone;
  const BatchSummary judged = calibrate_batch(wide, plain);
  ASSERT_TRUE(judged.tyre_selection.judges_plain);
  for (const TyreCandidate& candidate : judged.tyre_selection.candidates)
    EXPECT_FALSE(candidate.needed) << judged.full_report();
  EXPECT_EQ(judged.model_spread_m[0], 0.0);
}

// The realistic circuit of a rear-driven car, worn tyres: its residuals are white (the generous
// odometry noise takes the slip in), yet the physical tyre terms fit it far better and put the
// circumferences at rest ~30 mm from what the drive rolled on. The iterative method's estimate
// of the rolled ones is off the true ones by many times its own sigma; judged, its sigma carries
// that gap, the verdict says why, and the result is refused: the gap is 25 of its own sigma.
TEST(ModelAdequacyBatch, AnEstimateThatTheTyreModelMovesCarriesThatGapInItsSigma) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.vehicle.wear_rl_mm = 1.5;
  scenario.vehicle.wear_rr_mm = 1.0;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive);
  const double truth_m = drive.true_params.circumference_rl_m;
  CalibrationConfig config;
  config.method = CalibrationMethod::kIterative;
  config.common.judge_model_adequacy = false;
  const CalibrationSummary bare = core(calibrate(log, config));
  ASSERT_TRUE(bare.usable()) << bare.message;
  EXPECT_GT(std::abs(bare.estimate.circumference_rl_m - truth_m), 3.0 * bare.sigma_rl_m());

  config.common.judge_model_adequacy = true;
  const CalibrationSummary judged = core(calibrate(log, config));
  EXPECT_EQ(judged.estimate.circumference_rl_m, bare.estimate.circumference_rl_m);
  EXPECT_LT(std::abs(judged.estimate.circumference_rl_m - truth_m), 3.0 * judged.sigma_rl_m());
  EXPECT_FALSE(judged.model_adequacy.explains);
  EXPECT_NE(judged.model_adequacy.verdict.find("tyre_model: physical fits it better"),
            std::string::npos)
      << judged.model_adequacy.verdict;
  // Contradicted at its own precision (the gap is many of its own sigma): not a result.
  EXPECT_EQ(judged.termination, Termination::kNotIdentifiable);
  EXPECT_NE(judged.message.find("calibrate with --method batch"), std::string::npos)
      << judged.message;
}

// The ideal circuit (3 laps) under a GNSS error of 2 m over `tau_s` on 5 cm of white noise,
// configured as 0.1 m of white noise (bench/honest_sigma.cpp's runs).
struct WanderingReceiver {
  Log log;
  double truth_rl_m = 0.0;
};
WanderingReceiver wandering_receiver(std::uint64_t seed, double tau_s) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  scenario.route.laps = 3;
  scenario.vehicle.wear_rl_mm = 1.5;
  scenario.vehicle.wear_rr_mm = 1.0;
  scenario.seeds.noise = seed;
  scenario.gnss.sigma_m = 0.05;
  scenario.gnss.gauss_markov_sigma_m = 2.0;
  scenario.gnss.gauss_markov_tau_s = tau_s;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  WanderingReceiver receiver{simulated_log(drive), drive.true_params.circumference_rl_m};
  receiver.log.gnss.sigma_m.clear();  // the configured 0.1 m applies
  return receiver;
}

CalibrationOptions claiming_white_gnss_noise() {
  CalibrationOptions claimed;
  claimed.reference.gnss_sigma_m = 0.1;
  return claimed;
}

double error_in_sigmas(const CalibrationSummary& s, double truth_m) {
  return std::abs(s.estimate.circumference_rl_m - truth_m) / s.sigma_rl_m();
}

// Run 12 (120 s): the iterative method trusts the configured noise and put c_RL +1.56 mm off at
// a sigma of 0.41 mm. Its judge's batch fit sees the noise in its residuals; under the noise they
// show, the batch's sigma is what no estimate from this log can beat, and the iterative estimate
// claims no less.
TEST(ModelAdequacyBatch, AnEstimateUnderAWrongGnssNoiseClaimsNoLessThanTheBatch) {
  const WanderingReceiver receiver = wandering_receiver(12, 120.0);
  const CalibrationOptions claimed = claiming_white_gnss_noise();
  CalibrationOptions unjudged = claimed;
  unjudged.judge_model_adequacy = false;
  const IterativeSummary trusting = calibrate_iterative(receiver.log, {}, unjudged);
  ASSERT_GT(error_in_sigmas(trusting, receiver.truth_rl_m), 3.0);
  const IterativeSummary judged = calibrate_iterative(receiver.log, {}, claimed);
  EXPECT_EQ(judged.estimate.circumference_rl_m, trusting.estimate.circumference_rl_m);
  EXPECT_LT(error_in_sigmas(judged, receiver.truth_rl_m), 3.0) << judged.full_report();
  EXPECT_GT(judged.sigma_rl_m(), 1.5 * trusting.sigma_rl_m());
  EXPECT_TRUE(judged.usable()) << judged.full_report();
  EXPECT_NE(judged.model_adequacy.verdict.find("the GNSS noise is not the configured one"),
            std::string::npos)
      << judged.model_adequacy.verdict;
}

// Run 33 (60 s): the batch under the noise shown, its track held as the judge's is, is +2.15 mm
// off at sigma 0.80 mm, the iterative estimate +2.65 mm. At the batch's sigma alone it was 3.3
// sigma off; the half millimetre between the two is this estimate's own error beyond the batch's,
// and its sigma carries it. (The batch by default fits this log's track under its prior,
// track_prior_test.cpp, and lands at +2.72 mm: the judge's fit is the held one.)
TEST(ModelAdequacyBatch, AnEstimateUnderAWrongGnssNoiseCarriesItsGapToTheBatch) {
  const WanderingReceiver receiver = wandering_receiver(33, 60.0);
  const CalibrationOptions claimed = claiming_white_gnss_noise();
  const IterativeSummary judged = calibrate_iterative(receiver.log, {}, claimed);
  BatchOptions held_track;
  held_track.tyre_model = TyreModelChoice::kNone;
  CalibrationOptions unjudged = claimed;
  unjudged.judge_model_adequacy = false;
  const BatchSummary batch = calibrate_batch(receiver.log, held_track, unjudged);
  ASSERT_FALSE(batch.track_under_prior);
  ASSERT_TRUE(batch.gnss_noise.adapted);
  const double gap_m = judged.estimate.circumference_rl_m - batch.estimate.circumference_rl_m;
  ASSERT_GT(std::abs(gap_m), 0.3e-3);  // the case, as measured
  // The batch's own sigma includes the terms it considers; the floor is at least its variance
  // plus the gap's square. Not the held track's share, which the batch here takes whole and the
  // judge only as far as its track under the prior leaves it (track_prior_test.cpp).
  const double batch_without_track_m =
      std::sqrt(std::pow(batch.sigma_rl_m(), 2) - std::pow(batch.track_sigma_m[0], 2));
  EXPECT_GE(judged.sigma_rl_m(), std::hypot(0.95 * batch_without_track_m, gap_m))
      << judged.full_report();
  EXPECT_LT(error_in_sigmas(judged, receiver.truth_rl_m), 3.0) << judged.full_report();
  EXPECT_NE(judged.model_adequacy.verdict.find("with this estimate's gap to the batch's"),
            std::string::npos)
      << judged.model_adequacy.verdict;
}

// The realistic urban drive (rear-driven, wear 1.5 / 1.0 mm) under a GNSS error of `sigma_m` over
// 10 s on 5 cm of white noise.
sim::SimulatedDrive urban_under_a_correlated_gnss_error(std::uint64_t seed, double sigma_m) {
  sim::Scenario scenario = load_scenario("urban");
  scenario.vehicle.wear_rl_mm = 1.5;
  scenario.vehicle.wear_rr_mm = 1.0;
  scenario.seeds.noise = seed;
  scenario.gnss.sigma_m = 0.05;
  scenario.gnss.gauss_markov_sigma_m = sigma_m;
  scenario.gnss.gauss_markov_tau_s = 10.0;
  return sim::simulate(scenario);
}

// The realistic urban drive (rear-driven, seed 1) under a GNSS error of 0.5 m over 10 s,
// configured as 0.1 m white. The judge's physical fit (the track free), solved under the
// configured noise, wandered and held every coefficient, and put the circumferences at rest
// 1.4 mm from the iterative estimate: its sigma claimed 2.9 mm at an error of -12.7 mm. Under
// the noise that the residuals show the fit identifies its coefficients and puts them 10.4 mm
// away, which the sigma carries.
TEST(ModelAdequacyBatch, ATyreFitThatWandersUnderAWrongNoiseIsTakenUnderTheNoiseShown) {
  const sim::SimulatedDrive drive = urban_under_a_correlated_gnss_error(1, 0.5);
  Log log = simulated_log(drive);
  log.gnss.sigma_m.clear();  // the configured 0.1 m applies
  const IterativeSummary judged = calibrate_iterative(log, {}, claiming_white_gnss_noise());
  const double error_m = judged.estimate.circumference_rl_m - drive.true_params.circumference_rl_m;
  ASSERT_GT(std::abs(error_m), 0.008);  // the case, as measured: the circumference rolled on
  EXPECT_LT(error_in_sigmas(judged, drive.true_params.circumference_rl_m), 3.0)
      << judged.full_report();
  EXPECT_NE(judged.model_adequacy.verdict.find("tyre_model: physical fits it better"),
            std::string::npos)
      << judged.model_adequacy.verdict;
  // Not "use auto": its fit under the configured noise wanders there too.
  EXPECT_NE(judged.model_adequacy.verdict.find("state that noise"), std::string::npos)
      << judged.model_adequacy.verdict;
}

// auto as well: a physical fit that wandered under the configured noise cannot be chosen, but it
// judges the plain fit by its fit under the noise shown, and the result says so.
TEST(ModelAdequacyBatch, AutoJudgesByAWanderingTyreFitUnderTheNoiseShownAndSaysSo) {
  const sim::SimulatedDrive drive = urban_under_a_correlated_gnss_error(3, 2.0);
  Log log = simulated_log(drive);
  log.gnss.sigma_m.clear();
  const BatchSummary fit = calibrate_batch(log, {}, claiming_white_gnss_noise());
  const double error_m = fit.estimate.circumference_rl_m - drive.true_params.circumference_rl_m;
  ASSERT_GT(std::abs(error_m), 0.008);  // the case, as measured
  EXPECT_LT(error_in_sigmas(fit, drive.true_params.circumference_rl_m), 3.0) << fit.full_report();
  const TyreModelSelection& selection = fit.tyre_selection;
  ASSERT_EQ(selection.chosen, "none") << fit.full_report();
  ASSERT_FALSE(selection.candidates.empty());
  const TyreCandidate& physical = selection.candidates.front();
  EXPECT_TRUE(physical.judged_under_noise_shown) << fit.full_report();
  EXPECT_EQ(selection.plain_gap_to, physical.model);
  EXPECT_NE(fit.full_report().find("did not settle under the configured GNSS noise"),
            std::string::npos)
      << fit.full_report();
  const nlohmann::json json = summary_to_json(fit, {});
  EXPECT_TRUE(json.at("tyre_selection").at("candidates").at(0).at("judged_under_noise_shown"));
}

}  // namespace
}  // namespace odocal
