// The tyre models through the batch, against known truth: an ideal drive whose wheels are
// re-counted as if each rolled a circumference that follows the driving state with known
// coefficients of the regression terms (the extended model's class exactly). The plain model is
// biased and does not explain the log; the extended one recovers circumferences and
// coefficients inside 3 sigma. How auto chooses: a tyre model where the log needs one, never a
// confident plain fit that it contradicts, the plain model on the ideal lap.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <tuple>

#include "../support/plain_bias_covered.hpp"
#include "../support/recounted_wheels.hpp"
#include "../support/test_scenarios.hpp"
#include "../support/unjudged_options.hpp"
#include "estimation/batch_fit.hpp"
#include "experiments/drifting_gnss.hpp"
#include "experiments/worn_circuit.hpp"
#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/estimation/drift_validation.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/estimation/iterative_calibration.hpp"
#include "odocal/io/calibration_io.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

constexpr TyreModel kTruth{-3e-6, 4e-4, 8e-3, 4e-3, -2e-2, 7e-4, 5e-4};
const VehicleBody kBody;

// 1 m GNSS: beside seven coefficients the circumference at rest is an extrapolation (docs/
// tyre-model.md), about 1 mm at 1 sigma with the scenario's 3 m.
sim::SimulatedDrive ideal_drive() {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  scenario.gnss.sigma_m = 1.0;
  return sim::simulate(scenario);  // 3 laps: a circumference to a millimetre beside 7 coefficients
}

Log ideal_lap() { return simulated_log(ideal_drive()); }

Log with_condition_dependent_tyres(const Log& ideal) {
  return testing::with_wheels_recounted(ideal, kTruth, kBody);
}

const EstimatedParameter& parameter(const BatchSummary& s, const std::string& name) {
  for (const EstimatedParameter& p : s.parameters)
    if (p.name == name) return p;
  throw std::runtime_error("no parameter " + name);
}

// Both rear circumferences inside 3 reported sigma of the truth.
void expect_inside_3_sigma(const CalibrationSummary& result, const OdometryParams& truth,
                           const std::string& report) {
  EXPECT_LT(std::abs(result.estimate.circumference_rl_m - truth.circumference_rl_m),
            3.0 * result.sigma_rl_m())
      << report;
  EXPECT_LT(std::abs(result.estimate.circumference_rr_m - truth.circumference_rr_m),
            3.0 * result.sigma_rr_m())
      << report;
}

const std::string kHockenheimTrack =
    std::string(ODOCAL_SOURCE_DIR) + "/../shared/data/tracks/hockenheim/track.csv";

// The circuit scenario (3 laps) on ../shared's Hockenheim track; none where it is absent.
std::optional<sim::Scenario> hockenheim_scenario() {
  if (!std::filesystem::exists(kHockenheimTrack)) return std::nullopt;
  sim::Scenario scenario = load_scenario("circuit");
  use_track_file(scenario, kHockenheimTrack);
  return scenario;
}

const std::string kHockenheimRaceline =
    std::string(ODOCAL_SOURCE_DIR) + "/../shared/data/tracks/hockenheim/raceline.csv";

// The circuit scenario (3 laps, rear-driven, its driver fishtailing out of the corners) on
// ../shared's Hockenheim racing line with worn tyres; none where it is absent.
std::optional<sim::Scenario> raceline_scenario(std::uint64_t seed) {
  if (!std::filesystem::exists(kHockenheimRaceline)) return std::nullopt;
  sim::Scenario scenario = load_scenario("circuit");
  use_track_file(scenario, kHockenheimRaceline);
  scenario.vehicle.wear_rl_mm = 1.5;
  scenario.vehicle.wear_rr_mm = 1.0;
  scenario.seeds.noise = scenario.seeds.trajectory = seed;
  return scenario;
}

TEST(TyreModelBatch, RecoversKnownCoefficientsWhereThePlainModelIsBiased) {
  const sim::SimulatedDrive drive = ideal_drive();
  const Log log = with_condition_dependent_tyres(simulated_log(drive));
  const double truth_m = drive.true_params.circumference_rl_m;
  ASSERT_DOUBLE_EQ(drive.true_params.circumference_rr_m, truth_m);

  BatchOptions plain_options;
  plain_options.tyre_model = TyreModelChoice::kNone;
  const BatchSummary plain = calibrate_batch(log, plain_options);
  EXPECT_FALSE(plain.model_adequacy.explains) << plain.model_adequacy.verdict;
  EXPECT_NE(plain.model_adequacy.verdict.find("tyre_model: physical"), std::string::npos);

  // The estimator alone: judged, the regression terms would carry their gap to the physical
  // terms, which do not describe these wheels exactly (4.3 mm: refused at 1 mm).
  BatchOptions extended_options;
  extended_options.tyre_model = TyreModelChoice::kExtended;
  const BatchSummary extended = calibrate_batch(log, extended_options, testing::unjudged_options());
  ASSERT_TRUE(extended.usable()) << extended.message;
  for (const auto& [name, truth] :
       {std::pair{"circumference_rl_m", truth_m}, std::pair{"circumference_rr_m", truth_m},
        std::pair{"tyre_speed_s2pm2", kTruth.k_speed_s2pm2},
        std::pair{"tyre_lateral_s2pm", kTruth.k_lateral_s2pm},
        std::pair{"tyre_drive_s2pm", kTruth.k_drive_s2pm},
        std::pair{"tyre_brake_s2pm", kTruth.k_brake_s2pm},
        std::pair{"tyre_turn_s2prad2", kTruth.k_turn_s2prad2},
        std::pair{"tyre_drive_lateral_s4pm2", kTruth.k_drive_lateral_s4pm2},
        std::pair{"tyre_brake_lateral_s4pm2", kTruth.k_brake_lateral_s4pm2}}) {
    const EstimatedParameter& p = parameter(extended, name);
    EXPECT_TRUE(p.estimated) << name;
    EXPECT_LT(std::abs(p.value - truth), 3.0 * p.sigma) << name << " " << p.value;
  }
  const double plain_error = std::abs(plain.estimate.circumference_rl_m - truth_m);
  const double extended_error = std::abs(extended.estimate.circumference_rl_m - truth_m);
  // Biased beyond its sigma as it fits; judged against the physical terms, its sigma carries the
  // gap to their circumferences at rest.
  const BatchSummary bare = calibrate_batch(log, plain_options, testing::unjudged_options());
  EXPECT_EQ(bare.estimate.circumference_rl_m, plain.estimate.circumference_rl_m)
      << plain.full_report();
  EXPECT_GT(plain_error, 3.0 * bare.sigma_rl_m());
  EXPECT_LT(plain_error, 3.0 * plain.sigma_rl_m()) << plain.full_report();
  EXPECT_LT(extended_error, plain_error);
  EXPECT_LT(extended.after.mean_position_m, plain.after.mean_position_m);

  // Held out: 60 s windows dead-reckoned with each calibration, the extended one through its
  // tyre model.
  const ReferenceTrajectory reference = compute_reference(log, CalibrationOptions{}.reference);
  const DriftValidation drift =
      validate_drift(log.wheels, with_tyre_model(log, extended.estimate, extended.tyre_model),
                     reference, plain.estimate, extended.estimate);
  EXPECT_LT(drift.calibrated_statistics.median_drift_percent,
            0.5 * drift.nominal_statistics.median_drift_percent);

  // auto tries the physical terms first; they too explain this log far better than the plain
  // model (its wheels follow speed, acceleration and turns), so the regression terms are not
  // tried. Choosing a model is calibrating as under it; the plain fit's solves were spent on the
  // comparison (with, where the plain fit adapted the GNSS noise, one more fit of each model
  // under that noise for its criterion).
  BatchOptions auto_options;
  auto_options.tyre_model = TyreModelChoice::kAuto;
  const BatchSummary chosen = calibrate_batch(log, auto_options);
  EXPECT_TRUE(chosen.tyre_selection.compared);
  EXPECT_EQ(chosen.tyre_selection.chosen, "physical") << chosen.full_report();
  EXPECT_EQ(chosen.tyre_selection.candidates.size(), 1u);
  BatchOptions physical_options;
  physical_options.tyre_model = TyreModelChoice::kPhysical;
  const BatchSummary physical = calibrate_batch(log, physical_options);
  EXPECT_EQ(chosen.estimate.circumference_rl_m, physical.estimate.circumference_rl_m);
  EXPECT_EQ(chosen.estimate.circumference_rr_m, physical.estimate.circumference_rr_m);
  EXPECT_EQ(chosen.solves, physical.solves);
  if (plain.gnss_noise.adapted)
    EXPECT_GT(chosen.tyre_selection.other_solves, plain.solves);
  else
    EXPECT_EQ(chosen.tyre_selection.other_solves, plain.solves);
}

TEST(TyreModelBatch, AutoDoesNotKeepAConfidentPlainFitThatTheTyreModelContradicts) {
  // The realistic circuit with a front-wheel-drive car: the plain fit lands ~14 mm off the
  // circumference at rest with a sigma of 0.13 mm; the physical terms, which win the BIC, put it
  // within a few millimetres with a sigma of ~1 mm. Even with a threshold that the physical fit's
  // sigma does not meet, auto does not fall back to the confident plain answer that the
  // physical fit contradicts: it reports the circumference as not identified.
  sim::Scenario scenario = load_scenario("circuit");
  scenario.dynamics.drivetrain = sim::Drivetrain::kFront;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive);
  const double truth_m = drive.true_params.circumference_rl_m;
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kAuto;
  options.max_sigma_circumference_m = 0.01;
  const BatchSummary free_choice = calibrate_batch(log, options);
  EXPECT_EQ(free_choice.tyre_selection.chosen, "physical") << free_choice.full_report();
  EXPECT_TRUE(free_choice.usable()) << free_choice.full_report();
  EXPECT_LT(std::abs(free_choice.estimate.circumference_rl_m - truth_m),
            3.0 * free_choice.sigma_rl_m());
  options.max_sigma_circumference_m = 5e-4;
  const BatchSummary strict = calibrate_batch(log, options);
  EXPECT_EQ(strict.tyre_selection.chosen, "physical") << strict.full_report();
  EXPECT_EQ(strict.estimate.circumference_rl_m, free_choice.estimate.circumference_rl_m);
  EXPECT_EQ(strict.termination, Termination::kNotIdentifiable) << strict.full_report();
}

TEST(TyreModelBatch, APlainFitJudgedByAWrongBodysPhysicalTermsCarriesTheirGap) {
  // The realistic circuit of a rear-driven car lower and heavier than vehicle.yaml's, with softer,
  // more load-sensitive tyres: the plain fit lands ~60 mm off at a sigma of 1.5 mm. The physical
  // terms, with the wrong body, win the criterion and judge: their gap to the plain fit is in its
  // sigma, which covers the error, and the fit is refused. (Until the slip divided the
  // circumference, 2026-11-30, their slip at the log's RMS state was judged no tyre, and the
  // regression terms judged.)
  sim::Scenario scenario = testing::with_low_heavy_body(load_scenario("circuit"));
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive);
  const double truth_m = drive.true_params.circumference_rl_m;
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kNone;
  options.max_sigma_circumference_m = 0.01;
  const BatchSummary bare = calibrate_batch(log, options, testing::unjudged_options());
  EXPECT_GT(std::abs(bare.estimate.circumference_rl_m - truth_m), 3.0 * bare.sigma_rl_m());
  const BatchSummary judged = calibrate_batch(log, options);
  const TyreModelSelection& selection = judged.tyre_selection;
  ASSERT_GE(selection.candidates.size(), 1u) << judged.full_report();
  EXPECT_EQ(selection.candidates[0].model, "physical");
  EXPECT_TRUE(selection.candidates[0].tyre);
  EXPECT_LT(selection.candidates[0].bic, selection.plain_bic);
  EXPECT_EQ(judged.estimate.circumference_rl_m, bare.estimate.circumference_rl_m)
      << judged.full_report();
  EXPECT_LT(std::abs(judged.estimate.circumference_rl_m - truth_m), 3.0 * judged.sigma_rl_m())
      << judged.full_report();
  EXPECT_EQ(judged.termination, Termination::kNotIdentifiable);
  EXPECT_NE(judged.model_adequacy.verdict.find("tyre_model: physical fits it better"),
            std::string::npos)
      << judged.model_adequacy.verdict;
}

TEST(TyreModelBatch, WhereAWrongBodyMakesThePhysicalTermsNoTyreTheRegressionTermsJudge) {
  // One lap of the realistic circuit (rear-driven, the true circumferences nominal), whose
  // vehicle.yaml puts 90 % of the car's weight on the rear axle (the car's: 54 %): the physical
  // terms, with that body and the track free, fit the log better but are no tyre; the regression
  // terms, which need no body, fit it better too and are a tyre. They judge the plain fit
  // (~31 mm off at a sigma of ~1.5 mm unjudged): its sigma carries their gap, and it is refused.
  // Under auto they stand; the iterative method's judge carries the same gap.
  // Built on the simulator's force in steps (actuator_time_constant_s 0, before 2026-12-05): with
  // the lag the plain fit is a candidate no more.
  sim::Scenario lap = testing::realistic_lap_on_track(0.0, 1);
  lap.dynamics.actuator_time_constant_s = 0.0;
  const sim::SimulatedDrive drive = sim::simulate(lap);
  Log log = simulated_log(drive);
  log.vehicle.body.rear_axle_load_share = 0.9;
  const double truth_m = drive.true_params.circumference_rl_m;
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  options.tyre_model = TyreModelChoice::kNone;
  const BatchSummary bare =
      testing::expect_the_track_held_covers_the_plain_bias(log, options, truth_m);
  const BatchSummary judged = calibrate_batch(log, options);
  const TyreModelSelection& selection = judged.tyre_selection;
  ASSERT_EQ(selection.candidates.size(), 2u) << judged.full_report();
  EXPECT_EQ(selection.candidates[0].model, "physical");
  EXPECT_FALSE(selection.candidates[0].tyre);
  EXPECT_EQ(selection.candidates[1].model, "extended");
  EXPECT_TRUE(selection.candidates[1].tyre);
  EXPECT_LT(selection.candidates[1].bic, selection.plain_bic);
  EXPECT_EQ(selection.plain_gap_to, "extended");
  EXPECT_EQ(judged.estimate.circumference_rl_m, bare.estimate.circumference_rl_m);
  EXPECT_LT(std::abs(judged.estimate.circumference_rl_m - truth_m), 3.0 * judged.sigma_rl_m())
      << judged.full_report();
  EXPECT_EQ(judged.termination, Termination::kNotIdentifiable);
  EXPECT_NE(judged.model_adequacy.verdict.find("tyre_model: extended fits it better"),
            std::string::npos)
      << judged.model_adequacy.verdict;

  // Under auto, with the track free as well, the physical terms have stood since their cornering
  // drag follows the front wheels' steer (2026-12-05: the drive slip at 0.099, a tyre's): 3.8 mm
  // off at a sigma of 3.6 mm. The regression terms stood before. Either is an answer that its
  // sigma covers; none, the plain fit, would not be.
  options.tyre_model = TyreModelChoice::kAuto;
  const BatchSummary chosen = calibrate_batch(log, options);
  EXPECT_NE(chosen.tyre_selection.chosen, "none") << chosen.full_report();
  EXPECT_LT(std::abs(chosen.estimate.circumference_rl_m - truth_m), 3.0 * chosen.sigma_rl_m())
      << chosen.full_report();

  const IterativeSummary iterative = calibrate_iterative(log);
  EXPECT_EQ(iterative.termination, Termination::kNotIdentifiable) << iterative.full_report();
  EXPECT_LT(std::abs(iterative.estimate.circumference_rl_m - truth_m), 3.0 * iterative.sigma_rl_m())
      << iterative.full_report();
  EXPECT_NE(iterative.model_adequacy.verdict.find("tyre_model: extended fits it better"),
            std::string::npos)
      << iterative.model_adequacy.verdict;
}

TEST(TyreModelBatch, AutoCarriesTheRegressionTermsGapWhereVehicleYamlsBodyMovesThePhysicalOnes) {
  // One lap of the realistic circuit (rear-driven), whose vehicle.yaml states a front-driven car:
  // the physical terms take the drive slip for none and stand ~50 mm off, and without their
  // witness their sigma (~3 mm) did not cover it. The regression terms, which need no body,
  // disagree beyond 3 combined sigma: the physical circumferences carry the gap, and the answer is
  // refused. With the body stated right the two agree and nothing is carried.
  const sim::SimulatedDrive drive = sim::simulate(testing::realistic_lap_on_track(0.0, 1));
  Log log = simulated_log(drive);
  const double truth_m = drive.true_params.circumference_rl_m;
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  options.tyre_model = TyreModelChoice::kAuto;
  const BatchSummary right = calibrate_batch(log, options);
  EXPECT_EQ(right.tyre_selection.chosen, "physical") << right.full_report();
  EXPECT_EQ(right.tyre_selection.chosen_gap_to, "") << right.full_report();
  EXPECT_LT(std::abs(right.estimate.circumference_rl_m - truth_m), 3.0 * right.sigma_rl_m());

  log.vehicle.body.drivetrain = Drivetrain::kFront;
  const BatchSummary wrong = calibrate_batch(log, options);
  const TyreModelSelection& selection = wrong.tyre_selection;
  EXPECT_EQ(selection.chosen, "physical") << wrong.full_report();
  EXPECT_EQ(selection.chosen_gap_to, "extended") << wrong.full_report();
  EXPECT_GT(selection.chosen_gap_sigmas, batch::kWitnessSigmas);
  const double error_m = std::abs(wrong.estimate.circumference_rl_m - truth_m);
  const double own_sigma_m = std::sqrt(wrong.sigma_rl_m() * wrong.sigma_rl_m() -
                                       wrong.model_spread_m[0] * wrong.model_spread_m[0]);
  EXPECT_GT(error_m, 3.0 * own_sigma_m) << wrong.full_report();
  EXPECT_LT(error_m, 3.0 * wrong.sigma_rl_m()) << wrong.full_report();
  EXPECT_EQ(wrong.termination, Termination::kNotIdentifiable);
  EXPECT_NE(wrong.model_adequacy.verdict.find("check vehicle.yaml's body"), std::string::npos)
      << wrong.model_adequacy.verdict;

  // Chosen by hand, the physical terms are witnessed alike (where `auto` also weighed the plain
  // model, its track width may settle a little differently).
  options.tyre_model = TyreModelChoice::kPhysical;
  const BatchSummary by_hand = calibrate_batch(log, options);
  EXPECT_NEAR(by_hand.estimate.circumference_rl_m, wrong.estimate.circumference_rl_m,
              0.1 * wrong.sigma_rl_m());
  EXPECT_GT(by_hand.model_spread_m[0], 3.0 * own_sigma_m) << by_hand.full_report();
  EXPECT_EQ(by_hand.termination, Termination::kNotIdentifiable);

  // Where the physical fit is refused on its own sigma (the default 1 mm), there is no answer to
  // guard: the witness is not fitted, and nothing is carried.
  options.tyre_model = TyreModelChoice::kAuto;
  options.max_sigma_circumference_m = BatchOptions{}.max_sigma_circumference_m;
  const BatchSummary refused = calibrate_batch(log, options);
  EXPECT_EQ(refused.tyre_selection.chosen, "physical") << refused.full_report();
  EXPECT_EQ(refused.termination, Termination::kNotIdentifiable) << refused.full_report();
  EXPECT_EQ(refused.tyre_selection.chosen_gap_to, "") << refused.full_report();
  EXPECT_EQ(refused.model_spread_m[0], 0.0);
  EXPECT_EQ(refused.estimate.circumference_rl_m, wrong.estimate.circumference_rl_m);
  EXPECT_LT(refused.solves + refused.tyre_selection.other_solves,
            wrong.solves + wrong.tyre_selection.other_solves);
}

TEST(TyreModelBatch, RegressionTermsChosenByHandCarryTheirGapToThePhysicalOnes) {
  // One lap of the realistic circuit (rear-driven) with a Doppler column, fitted by it: the
  // regression terms extrapolate to rest ~21 mm off at a sigma of ~0.9 mm of the log's own, as
  // if identified. The physical terms, fitted beside them as under auto, put the circumferences
  // within a few mm of the truth: the regression terms carry the gap, which covers their error.
  sim::Scenario scenario = testing::realistic_lap_on_track(0.0, 1);
  scenario.gnss.speed_sigma_mps = 0.05;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive);
  const double truth_m = drive.true_params.circumference_rl_m;
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kExtended;
  options.gnss_speed_sigma_mps = 0.05;

  const BatchSummary alone = calibrate_batch(log, options, testing::unjudged_options());
  const double error_m = std::abs(alone.estimate.circumference_rl_m - truth_m);
  EXPECT_GT(error_m, 3.0 * alone.sigma_rl_m()) << alone.full_report();
  EXPECT_EQ(alone.model_spread_m[0], 0.0);

  const BatchSummary judged = calibrate_batch(log, options);
  EXPECT_NO_THROW(parameter(judged, "tyre_speed_s2pm2"));
  EXPECT_EQ(judged.tyre_selection.chosen_gap_to, "physical") << judged.full_report();
  EXPECT_GT(judged.tyre_selection.other_solves, 0);
  EXPECT_EQ(judged.estimate.circumference_rl_m, alone.estimate.circumference_rl_m);
  // Their misfit widens the Doppler speed's noise 56 times; a latency takes some of it at 10
  // sigma, but leaves the noise 14 times the configured: not a lag's.
  ASSERT_TRUE(judged.latency_detection.has_value()) << judged.full_report();
  EXPECT_TRUE(judged.latency_detection->by_doppler_noise);
  EXPECT_FALSE(judged.latency_detection->taken) << judged.full_report();
  EXPECT_NE(judged.full_report().find("not a lag's, kept without the latency"), std::string::npos)
      << judged.full_report();
  EXPECT_GT(judged.model_spread_m[0], 0.5 * error_m) << judged.full_report();
  EXPECT_LT(error_m, 3.0 * judged.sigma_rl_m()) << judged.full_report();
  EXPECT_LT(std::abs(judged.estimate.circumference_rr_m - drive.true_params.circumference_rr_m),
            3.0 * judged.sigma_rr_m())
      << judged.full_report();
  EXPECT_EQ(judged.termination, Termination::kNotIdentifiable) << judged.full_report();
}

TEST(TyreModelBatch, APlainFitThatANoTyreModelExplainsDecisivelyBetterCarriesItsGap) {
  // The lower, heavier car on tyres far softer than a road tyre's (a slip stiffness of 8 per unit
  // load; road tyres 10-30), one lap of the realistic circuit: the plain fit lands ~65 mm off at
  // a sigma of ~8 mm. The physical terms fit the log decisively better but are no tyre (their
  // slip coefficient, ~0.14, beyond kMaxSlipCoefficient), and so are the regression terms: the
  // plain fit stood, unjudged, confident and wrong. It now carries its gap to the physical fit,
  // under auto and under none alike (and the iterative method's estimate likewise), and is
  // refused with a sigma that covers its error.
  sim::Scenario scenario = testing::with_low_heavy_body(load_scenario("circuit"));
  scenario.dynamics.slip_stiffness_per_load = 8.0;
  // Built on the simulator's force in steps (actuator_time_constant_s 0, before 2026-12-05): with
  // the lag the regression terms explain this lap.
  scenario.dynamics.actuator_time_constant_s = 0.0;
  scenario.route.laps = 1;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive);
  const double truth_m = drive.true_params.circumference_rl_m;
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  options.tyre_model = TyreModelChoice::kNone;
  const BatchSummary bare =
      testing::expect_the_track_held_covers_the_plain_bias(log, options, truth_m);
  for (const TyreModelChoice choice : {TyreModelChoice::kAuto, TyreModelChoice::kNone}) {
    options.tyre_model = choice;
    const BatchSummary judged = calibrate_batch(log, options);
    const TyreModelSelection& selection = judged.tyre_selection;
    EXPECT_EQ(selection.chosen, "none") << judged.full_report();
    EXPECT_EQ(selection.plain_gap_to, "physical") << judged.full_report();
    ASSERT_GE(selection.candidates.size(), 1u);
    const TyreCandidate& physical = selection.candidates[0];
    EXPECT_FALSE(physical.tyre);
    EXPECT_LT(physical.bic, selection.plain_bic - batch::kDecisiveBic);
    // Under none the same plain fit (auto's stands with the track freed, 26 mm from it).
    if (choice == TyreModelChoice::kNone) {
      EXPECT_EQ(judged.estimate.circumference_rl_m, bare.estimate.circumference_rl_m)
          << judged.full_report();
      // The misfit widens the fixes (2.2 times), and a latency takes part of it (327 ms at 9
      // sigma, leaving 1.56 times): not the whole, so not taken.
      ASSERT_TRUE(judged.latency_detection.has_value()) << judged.full_report();
      EXPECT_TRUE(judged.latency_detection->by_gnss_noise);
      EXPECT_TRUE(judged.latency_detection->significant);
      EXPECT_FALSE(judged.latency_detection->taken);
      EXPECT_NE(judged.full_report().find("not a lag's alone"), std::string::npos);
    }
    EXPECT_LT(std::abs(judged.estimate.circumference_rl_m - truth_m), 3.0 * judged.sigma_rl_m())
        << judged.full_report();
    EXPECT_EQ(judged.termination, Termination::kNotIdentifiable);
    EXPECT_NE(judged.model_adequacy.verdict.find("but it is no tyre"), std::string::npos)
        << judged.model_adequacy.verdict;
  }
  // The iterative method is refused as well. Until the simulator's load transfer came from the
  // body's own acceleration (2026-12-05) its judge carried the same gap: its sigma covered its
  // error, and its message did not send the user to the batch's auto, which refuses it too. Since,
  // its estimate (~75 mm off) dead-reckons the log worse than the nominal circumferences, which
  // refuses it before the judge: implausible, the model not fitting this log.
  const IterativeSummary iterative = calibrate_iterative(log);
  if (iterative.termination == Termination::kNotIdentifiable) {
    EXPECT_LT(std::abs(iterative.estimate.circumference_rl_m - truth_m),
              3.0 * iterative.sigma_rl_m())
        << iterative.full_report();
    EXPECT_NE(iterative.message.find("but that model is no tyre"), std::string::npos)
        << iterative.message;
  } else {
    EXPECT_EQ(iterative.termination, Termination::kImplausible) << iterative.full_report();
    EXPECT_NE(iterative.message.find("worse than the nominal parameters"), std::string::npos)
        << iterative.message;
  }
}

TEST(TyreModelBatch, AutoDoesNotTakeATrackThatVehicleYamlGetsWrongForTyres) {
  // An ideal lap whose wheels run on a track 10 % wider than vehicle.yaml states: the wheels'
  // heading turns with the curvature, which the load terms mimic as load transfer. With the
  // track held they won the criterion and put the circumferences 43 mm off at a sigma of 3.3 mm;
  // the plain model with the track freed fits the log better, and stands, with the wider track.
  const sim::SimulatedDrive drive = sim::simulate(testing::ideal_lap_on_track(1.76));
  const Log log = simulated_log(drive);
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  const BatchSummary chosen = calibrate_batch(log, options);
  EXPECT_EQ(chosen.tyre_selection.chosen, "none") << chosen.full_report();
  EXPECT_TRUE(chosen.tyre_selection.plain_track_free);
  ASSERT_FALSE(chosen.tyre_selection.candidates.empty());
  const TyreCandidate& physical = chosen.tyre_selection.candidates[0];
  EXPECT_LT(physical.held_track_bic, chosen.tyre_selection.plain_bic);
  EXPECT_FALSE(physical.beyond_track);
  EXPECT_NE(chosen.full_report().find("plain, the track width free"), std::string::npos);
  EXPECT_NE(chosen.full_report().find("check track_width_m"), std::string::npos);
  EXPECT_NEAR(chosen.estimate.track_width_m, 1.76, 3.0 * chosen.parameters[2].sigma);
  EXPECT_LT(std::abs(chosen.estimate.circumference_rl_m - drive.true_params.circumference_rl_m),
            3.0 * chosen.sigma_rl_m())
      << chosen.full_report();
}

TEST(TyreModelBatch, AutoFreesTheTrackOfATyreModelWhereVehicleYamlGetsItWrong) {
  // The realistic circuit (rear-driven, one lap) on a track 10 % wider than vehicle.yaml states:
  // the tyres slip, so the physical terms beat the plain model even with its track freed. With
  // the track held they took the track's share as load transfer too and put the circumferences
  // at rest 32.6 mm off at a sigma of 4.4 mm; fitted with it free, they land within their sigma
  // and find the wider track.
  const sim::SimulatedDrive drive = sim::simulate(testing::realistic_lap_on_track(1.76, 1));
  const Log log = simulated_log(drive);
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  const BatchSummary chosen = calibrate_batch(log, options);
  ASSERT_TRUE(chosen.usable()) << chosen.full_report();
  EXPECT_EQ(chosen.tyre_selection.chosen, "physical") << chosen.full_report();
  const TyreCandidate& physical = chosen.tyre_selection.candidates.at(0);
  EXPECT_TRUE(physical.track_free);
  EXPECT_LT(physical.free_track_bic, physical.held_track_bic);
  EXPECT_NEAR(chosen.estimate.track_width_m, 1.76, 3.0 * chosen.parameters[2].sigma);
  for (const auto& [estimate, truth, sigma] :
       {std::tuple{chosen.estimate.circumference_rl_m, drive.true_params.circumference_rl_m,
                   chosen.sigma_rl_m()},
        std::tuple{chosen.estimate.circumference_rr_m, drive.true_params.circumference_rr_m,
                   chosen.sigma_rr_m()}}) {
    EXPECT_LT(std::abs(estimate - truth), 3.0 * sigma) << chosen.full_report();
    EXPECT_LT(std::abs(estimate - truth), 0.005) << chosen.full_report();
  }
  EXPECT_NE(chosen.full_report().find("physical, the track width free"), std::string::npos);
  EXPECT_NE(chosen.full_report().find("check track_width_m"), std::string::npos);
}

TEST(TyreModelBatch, AutoDoubtsTheTrackThatThePlainFitTakesForGnssError) {
  // The realistic circuit (rear-driven, one lap, seed 3) on a track 6 % narrower than stated:
  // the plain fit's GNSS noise adaptation takes its misfit in as correlated GNSS error of
  // metres; it lands far off at a sigma of a few millimetres. (Until the simulator's load transfer
  // came from the body's own acceleration, 2026-12-05, its heading residual hardly followed the
  // curvature; it does now, and the model check says so.) The physical terms that win the
  // criterion show the track: auto fits them with it free as well.
  const sim::SimulatedDrive drive = sim::simulate(testing::realistic_lap_on_track(1.5, 3));
  const Log log = simulated_log(drive);
  const double truth_m = drive.true_params.circumference_rl_m;
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  options.tyre_model = TyreModelChoice::kNone;
  options.track_width_uncertainty = 0.0;  // the track taken as exact: the plain fit's own sigma
  const BatchSummary plain = calibrate_batch(log, options, testing::unjudged_options());
  ASSERT_TRUE(plain.usable()) << plain.full_report();
  EXPECT_GT(std::abs(plain.estimate.circumference_rl_m - truth_m), 3.0 * plain.sigma_rl_m());
  options.track_width_uncertainty = BatchOptions{}.track_width_uncertainty;
  options.tyre_model = TyreModelChoice::kAuto;
  const BatchSummary chosen = calibrate_batch(log, options);
  ASSERT_TRUE(chosen.usable()) << chosen.full_report();
  EXPECT_EQ(chosen.tyre_selection.chosen, "physical") << chosen.full_report();
  EXPECT_TRUE(chosen.tyre_selection.candidates.at(0).track_free);
  EXPECT_NEAR(chosen.estimate.track_width_m, 1.5, 3.0 * chosen.parameters[2].sigma);
  EXPECT_LT(std::abs(chosen.estimate.circumference_rl_m - truth_m), 3.0 * chosen.sigma_rl_m())
      << chosen.full_report();
  EXPECT_LT(std::abs(chosen.estimate.circumference_rl_m - truth_m), 0.005) << chosen.full_report();
}

TEST(TyreModelBatch, AutoHoldsARightTrackThatFreedDeadReckonsTheLogWorse) {
  // 3 laps of Hockenheim, front-driven, a driver who shares the grip with the turn, the track as
  // vehicle.yaml states it, seed 2: the plain fit's heading residual follows the curvature, so
  // the track is in doubt, and the physical terms' criterion is lower with it free (by 0.8). The
  // freed track took up part of the model's misfit: the log dead-reckons 17.9 m with it and
  // 16.6 m with the stated one, whose fit therefore stands. (Seed 1 until the physical terms'
  // slip divided the circumference, 2026-11-30: there the freed track now dead-reckons the log
  // better, 9.5 m against 9.7 m, and stands, as it should.)
  std::optional<sim::Scenario> hockenheim = hockenheim_scenario();
  if (!hockenheim) GTEST_SKIP() << "shared data absent: " << kHockenheimTrack;
  sim::Scenario& scenario = *hockenheim;
  scenario.dynamics.drivetrain = sim::Drivetrain::kFront;
  scenario.driver.friction_ellipse = true;
  scenario.driver.max_power_wpkg = 80.0;
  scenario.seeds.noise = scenario.seeds.trajectory = 2;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive);
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  const BatchSummary chosen = calibrate_batch(log, options);
  ASSERT_TRUE(chosen.usable()) << chosen.full_report();
  EXPECT_EQ(chosen.tyre_selection.chosen, "physical") << chosen.full_report();
  const TyreCandidate& physical = chosen.tyre_selection.candidates.at(0);
  EXPECT_LT(physical.free_track_bic, physical.held_track_bic);
  EXPECT_FALSE(physical.track_free);
  EXPECT_LT(physical.held_track_score_m, physical.free_track_score_m);
  EXPECT_EQ(chosen.estimate.track_width_m, chosen.nominal.track_width_m);
  EXPECT_NEAR(chosen.after.mean_position_m + 10.0 * chosen.after.mean_heading_rad,
              physical.held_track_score_m, 1e-6);
  for (const auto& [estimate, truth, sigma] :
       {std::tuple{chosen.estimate.circumference_rl_m, drive.true_params.circumference_rl_m,
                   chosen.sigma_rl_m()},
        std::tuple{chosen.estimate.circumference_rr_m, drive.true_params.circumference_rr_m,
                   chosen.sigma_rr_m()}}) {
    EXPECT_LT(std::abs(estimate - truth), 3.0 * sigma) << chosen.full_report();
  }
  EXPECT_NE(chosen.full_report().find("the track held; free"), std::string::npos);
  EXPECT_NE(chosen.full_report().find("dead-reckoning the log"), std::string::npos);
}

TEST(TyreModelBatch, AutoDoesNotHoldAWrongTrackThatDeadReckonsAsWell) {
  // The realistic circuit (3 laps, front-driven, seed 1) on a track 6 % narrower than stated:
  // the physical terms' criterion is 2500 lower with the track free, yet the log dead-reckons
  // 21.4 m with the stated track and 21.7 m with the freed one. The held fit's heading residual
  // follows the curvature (rho 0.71), so its dead reckoning is not compared: held, the
  // circumference at rest was 2.1 mm off at a sigma of 0.7 mm.
  sim::Scenario scenario = load_scenario("circuit");
  scenario.vehicle.effective_track_width_m = 1.5;
  scenario.dynamics.drivetrain = sim::Drivetrain::kFront;
  scenario.seeds.noise = scenario.seeds.trajectory = 1;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive);
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  const BatchSummary chosen = calibrate_batch(log, options);
  ASSERT_TRUE(chosen.usable()) << chosen.full_report();
  EXPECT_EQ(chosen.tyre_selection.chosen, "physical") << chosen.full_report();
  const TyreCandidate& physical = chosen.tyre_selection.candidates.at(0);
  EXPECT_TRUE(physical.track_free) << chosen.full_report();
  EXPECT_TRUE(std::isnan(physical.held_track_score_m));
  EXPECT_NEAR(chosen.estimate.track_width_m, 1.5, 3.0 * chosen.parameters[2].sigma);
  const double error_m = chosen.estimate.circumference_rl_m - drive.true_params.circumference_rl_m;
  EXPECT_LT(std::abs(error_m), 3.0 * chosen.sigma_rl_m()) << chosen.full_report();
  EXPECT_LT(std::abs(error_m), 0.001) << chosen.full_report();
}

TEST(TyreModelBatch, AutoRefusesAPlainFitThatTheTyreModelMovesBeyondTheThreshold) {
  // The realistic urban drive with a rear-driven car (2 km; seeds 3): the mean drive slip puts
  // the plain fit's circumferences ~11 mm short at a sigma of 0.6 mm. The physical terms win the
  // BIC and land within a few millimetres, at a sigma of ~3 mm: not identified to the default
  // 1 mm, and within their own 3 sigma of the plain fit. That must not let the plain fit stand:
  // widened by the gap, its sigma would be far above the threshold. Auto reports the physical
  // fit, not identified, and does not go on to the regression terms.
  sim::Scenario scenario = load_scenario("urban");
  scenario.dynamics.drivetrain = sim::Drivetrain::kRear;
  scenario.seeds.noise = 3;
  scenario.seeds.trajectory = 3;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive);
  const double truth_m = drive.true_params.circumference_rl_m;
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kNone;
  const BatchSummary plain = calibrate_batch(log, options, testing::unjudged_options());
  ASSERT_TRUE(plain.usable()) << plain.full_report();
  ASSERT_GT(std::abs(plain.estimate.circumference_rl_m - truth_m), 3.0 * plain.sigma_rl_m());
  // Chosen by hand and judged, the plain fit carries that gap itself.
  const BatchSummary judged = calibrate_batch(log, options);
  EXPECT_EQ(judged.termination, Termination::kNotIdentifiable) << judged.full_report();
  EXPECT_LT(std::abs(judged.estimate.circumference_rl_m - truth_m), 3.0 * judged.sigma_rl_m());
  options.tyre_model = TyreModelChoice::kAuto;
  const BatchSummary chosen = calibrate_batch(log, options);
  EXPECT_EQ(chosen.tyre_selection.chosen, "physical") << chosen.full_report();
  EXPECT_EQ(chosen.tyre_selection.candidates.size(), 1u) << chosen.full_report();
  EXPECT_EQ(chosen.termination, Termination::kNotIdentifiable) << chosen.full_report();
  EXPECT_LT(std::abs(chosen.estimate.circumference_rl_m - truth_m),
            std::abs(plain.estimate.circumference_rl_m - truth_m) / 2.0);
  EXPECT_LT(std::abs(chosen.estimate.circumference_rl_m - truth_m), 3.0 * chosen.sigma_rl_m());
}

TEST(TyreModelBatch, APlainFitThatATyreModelTiesCarriesTheWeighedGap) {
  // One lap of the realistic urban drive (1 km) with a front-driven car, seed 1: the rear wheels'
  // brake slip puts
  // the plain fit 5.5 mm long at a sigma of 0.89 mm. The physical terms (1.2 mm off at 2.1 mm)
  // fit the log about as well as the plain model with the track freed (BIC 1.5 above it), so auto
  // kept the plain fit, usable and 6 sigma off. The criteria weigh the two, and the plain
  // circumferences carry that share of their gap: refused at the default 1 mm, the error inside
  // 3 sigma, and the verdict saying why; chosen by hand and judged, the same.
  const sim::SimulatedDrive drive =
      sim::simulate(testing::realistic_urban_lap(sim::Drivetrain::kFront, 1));
  const Log log = simulated_log(drive);
  const double truth_m = drive.true_params.circumference_rl_m;
  BatchOptions options;  // auto
  const BatchSummary chosen = calibrate_batch(log, options);
  SCOPED_TRACE(chosen.full_report());
  const TyreModelSelection& selection = chosen.tyre_selection;
  ASSERT_EQ(selection.chosen, "none");
  ASSERT_EQ(selection.plain_gap_to, "physical");
  const TyreCandidate& physical = selection.candidates.front();
  const double excess = physical.bic - selection.compared_plain_bic();
  ASSERT_GE(excess, 0.0);
  ASSERT_LT(excess, batch::kDecisiveBic);
  const double gap_m = std::abs(chosen.estimate.circumference_rl_m - physical.circumference[0]);
  EXPECT_NEAR(chosen.model_spread_m[0], batch::tie_gap_share(excess) * gap_m, 1e-9);
  EXPECT_NEAR(selection.plain_gap_share, batch::tie_gap_share(excess), 1e-12);
  EXPECT_EQ(summary_to_json(chosen, {}).at("tyre_selection").at("plain_gap_share"),
            selection.plain_gap_share);
  EXPECT_GT(std::abs(chosen.estimate.circumference_rl_m - truth_m), 0.004);
  EXPECT_LT(std::abs(chosen.estimate.circumference_rl_m - truth_m), 3.0 * chosen.sigma_rl_m());
  EXPECT_EQ(chosen.termination, Termination::kNotIdentifiable);
  EXPECT_NE(chosen.model_adequacy.verdict.find("tyre_model: physical fits it about as well"),
            std::string::npos);
  EXPECT_NE(chosen.full_report().find("it fits the log about as well"), std::string::npos);
  options.tyre_model = TyreModelChoice::kNone;
  const BatchSummary judged = calibrate_batch(log, options);
  EXPECT_EQ(judged.tyre_selection.plain_gap_to, "physical") << judged.full_report();
  EXPECT_GT(judged.tyre_selection.plain_gap_share, 0.0);
  EXPECT_LT(judged.tyre_selection.plain_gap_share, 1.0);
  EXPECT_EQ(judged.termination, Termination::kNotIdentifiable) << judged.full_report();
  EXPECT_LT(std::abs(judged.estimate.circumference_rl_m - truth_m), 3.0 * judged.sigma_rl_m());
}

TEST(TyreModelBatch, AutoTakesThePhysicalTermsWherePinnedAndThePlainFitIsOff) {
  // The ideal circuit whose wheels roll a little smaller under load (the radius term alone: in a
  // turn one wheel gains about what the other loses, so the plain fit's circumferences move
  // little). Until 2026-12-06 this was the log where the physical terms, unidentified (sigma
  // 0.91 mm), agreed with the plain fit and auto kept it (+0.56 mm at a sigma of 0.13 mm, the
  // track freed): the test of that branch. Since the gyro's turn is the trapezoid of its samples
  // (docs/batch-calibration.md), the physical terms with the track freed pin the circumference
  // on every noise seed tried (1-7: sigma 0.28-0.37 mm, within 0.13 mm of the truth), and auto
  // takes them. The branch where an agreeing plain fit stands has its own test below
  // (AutoKeepsAnIdentifiedPlainFitThatAnUnidentifiedTyreFitAgreesWith).
  TyreModel load;
  load.k_load_s2pm = 1e-3;
  const auto [drive, log] = testing::ideal_circuit_recounted(load, 0.0, 4);
  BatchOptions options;
  options.heading_tick_smoothing_s = 0.0;
  options.tyre_model = TyreModelChoice::kNone;
  const BatchSummary plain = calibrate_batch(log, options, testing::unjudged_options());
  options.tyre_model = TyreModelChoice::kAuto;
  const BatchSummary chosen = calibrate_batch(log, options);
  const double truth_m = drive.true_params.circumference_rl_m;
  EXPECT_EQ(chosen.tyre_selection.chosen, "physical") << chosen.full_report();
  EXPECT_TRUE(chosen.usable()) << chosen.full_report();
  EXPECT_LT(std::abs(chosen.estimate.circumference_rl_m - truth_m), 3.0 * chosen.sigma_rl_m())
      << chosen.full_report();
  EXPECT_GT(std::abs(plain.estimate.circumference_rl_m - truth_m), 3.0 * plain.sigma_rl_m())
      << plain.full_report();
  EXPECT_LT(std::abs(chosen.estimate.circumference_rl_m - truth_m),
            std::abs(plain.estimate.circumference_rl_m - truth_m) / 2.0);
}

TEST(TyreModelBatch, AutoKeepsAnIdentifiedPlainFitThatAnUnidentifiedTyreFitAgreesWith) {
  // The ideal circuit (1 m fixes) whose wheels roll smaller by 5e-4 s^2/m of their load change,
  // calibrated to a strict 0.15 mm: the physical terms win the criterion, 0.05 mm from the truth,
  // but report a sigma of 0.18 mm (the body's uncertainty in it; 0.05 mm bare), not identified.
  // The plain fit, 0.06 mm away from them, is identified with that gap in its sigma: auto keeps
  // it, usable, rather than refuse the log. (Until 2026-12-07 auto judged the physical fit
  // identified by its bare sigma, stood on it and refused.)
  TyreModel load;
  load.k_load_s2pm = 5e-4;
  const auto [drive, log] = testing::ideal_circuit_recounted(load, 1.0);
  const double truth_m = drive.true_params.circumference_rl_m;
  BatchOptions options;
  options.max_sigma_circumference_m = 1.5e-4;
  options.tyre_model = TyreModelChoice::kPhysical;
  const BatchSummary physical = calibrate_batch(log, options, testing::unjudged_options());
  ASSERT_GT(std::max(physical.sigma_rl_m(), physical.sigma_rr_m()),
            options.max_sigma_circumference_m)
      << physical.full_report();
  EXPECT_FALSE(physical.usable());

  options.tyre_model = TyreModelChoice::kAuto;
  const BatchSummary chosen = calibrate_batch(log, options);
  SCOPED_TRACE(chosen.full_report());
  const TyreModelSelection& selection = chosen.tyre_selection;
  EXPECT_EQ(selection.chosen, "none");
  ASSERT_EQ(selection.candidates.size(), 1u);  // it confirms the plain fit: no regression terms
  const TyreCandidate& candidate = selection.candidates.front();
  EXPECT_EQ(candidate.model, "physical");
  EXPECT_LT(candidate.bic, selection.compared_plain_bic());
  EXPECT_FALSE(candidate.needed);
  // The plain circumferences carry their whole gap to the physical ones, and stay identified.
  EXPECT_EQ(selection.plain_gap_to, "physical");
  EXPECT_EQ(selection.plain_gap_share, 1.0);
  for (std::size_t w = 0; w < 2; ++w) {
    const double estimate_m =
        w == 0 ? chosen.estimate.circumference_rl_m : chosen.estimate.circumference_rr_m;
    EXPECT_NEAR(chosen.model_spread_m[w], std::abs(estimate_m - candidate.circumference[w]), 1e-9);
  }
  EXPECT_TRUE(chosen.usable());
  EXPECT_LE(chosen.sigma_rl_m(), options.max_sigma_circumference_m);
  EXPECT_LT(std::abs(chosen.estimate.circumference_rl_m - truth_m), 3.0 * chosen.sigma_rl_m());
  EXPECT_NE(chosen.full_report().find("were not identified and agree with the plain fit's"),
            std::string::npos);
  EXPECT_NE(chosen.model_adequacy.verdict.find("auto keeps the plain fit"), std::string::npos);
  EXPECT_EQ(chosen.model_adequacy.verdict.find("use the batch's tyre_model: auto"),
            std::string::npos);
}

TEST(TyreModelBatch, AutoKeepsThePlainModelWhereTheLogNeedsNoMore) {
  BatchOptions auto_options;
  auto_options.tyre_model = TyreModelChoice::kAuto;
  const Log log = ideal_lap();
  const BatchSummary chosen = calibrate_batch(log, auto_options);
  EXPECT_TRUE(chosen.tyre_selection.compared);
  EXPECT_TRUE(chosen.tyre_model.plain()) << chosen.full_report();
  ASSERT_EQ(chosen.tyre_selection.candidates.size(), 2u);  // physical, then extended
  for (const TyreCandidate& candidate : chosen.tyre_selection.candidates)
    EXPECT_GT(candidate.bic, chosen.tyre_selection.plain_bic) << candidate.model;
  // Keeping the plain model is calibrating as under none, not a plain model re-solved from where
  // the extended fit left the problem.
  BatchOptions plain_options;
  plain_options.tyre_model = TyreModelChoice::kNone;
  const BatchSummary plain = calibrate_batch(log, plain_options);
  // Chosen by hand, the plain fit is judged against the physical terms, which do not win here.
  EXPECT_TRUE(plain.tyre_selection.judges_plain);
  ASSERT_EQ(plain.tyre_selection.candidates.size(), 1u);
  EXPECT_FALSE(plain.tyre_selection.candidates[0].needed);
  EXPECT_EQ(plain.model_spread_m[0], 0.0);
  EXPECT_EQ(chosen.estimate.circumference_rl_m, plain.estimate.circumference_rl_m);
  EXPECT_EQ(chosen.estimate.circumference_rr_m, plain.estimate.circumference_rr_m);
  EXPECT_NEAR(chosen.sigma_rl_m(), plain.sigma_rl_m(), 1e-6 * plain.sigma_rl_m());
  EXPECT_EQ(chosen.solves, plain.solves);
  EXPECT_GT(chosen.tyre_selection.other_solves, 0);
}

TEST(TyreModelBatch, AutoComparesUnderTheGnssNoiseTheResidualsShow) {
  // An ideal drive (no tyre effect in it) whose GNSS error is 5 cm of white noise on a
  // Gauss-Markov error of 0.5 m over 30 s, configured as 0.1 m of white noise and with no
  // sigma_m column (bench/honest_sigma.cpp, run 28). Compared under the configured noise, the
  // physical terms won the criterion by following part of that error, and the circumferences
  // moved 2 mm at a sigma of 0.43 mm; compared under the noise the plain fit found, the plain
  // model is kept and its error is inside 3 sigma.
  const auto [scenario, drive, log, claimed] =
      experiments::drifting_gnss_drive(experiments::worn_ideal_circuit(3, 28), 0.5, 30.0);
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kAuto;
  const BatchSummary chosen = calibrate_batch(log, options, claimed);
  ASSERT_TRUE(chosen.gnss_noise.adapted) << chosen.full_report();
  EXPECT_TRUE(chosen.tyre_model.plain()) << chosen.full_report();
  expect_inside_3_sigma(chosen, drive.true_params, chosen.full_report());
}

TEST(TyreModelBatch, AutoKeepsThePlainFitWhereTheExtendedOneDeadReckonsWorse) {
  // 100 laps of the ideal circuit, a million samples: the BIC prefers the extended model for
  // effects of a few 1e-5, and its circumferences, 17 um from the plain fit's, dead-reckon the
  // whole log worse than the nominal parameters (25 m against 1.6 m): not usable. The plain fit
  // is, and stands.
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  scenario.route.laps = 100;
  const Log log = simulated_log(sim::simulate(scenario));
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kAuto;
  const BatchSummary chosen = calibrate_batch(log, options);
  bool refused = false;
  for (const TyreCandidate& candidate : chosen.tyre_selection.candidates) {
    if (candidate.dead_reckons) continue;
    EXPECT_LT(candidate.bic, chosen.tyre_selection.plain_bic) << candidate.model;
    refused = true;
  }
  EXPECT_TRUE(refused) << chosen.full_report();
  EXPECT_TRUE(chosen.tyre_model.plain()) << chosen.full_report();
  EXPECT_TRUE(chosen.usable()) << chosen.full_report();
  EXPECT_NE(chosen.full_report().find("dead-reckons worse"), std::string::npos);
  options.tyre_model = TyreModelChoice::kNone;
  const BatchSummary plain = calibrate_batch(log, options);
  EXPECT_EQ(chosen.estimate.circumference_rl_m, plain.estimate.circumference_rl_m);
  EXPECT_EQ(chosen.after.mean_position_m, plain.after.mean_position_m);
}

TEST(TyreModelBatch, AdaptingTheGnssNoiseDoesNotCarryTheTyreModelIntoNonsense) {
  // 3 laps of Hockenheim, front-wheel drive: the rear wheels slip under the brakes' rear share.
  // With the five coefficients of 2026-11-24, which could not follow it, the GNSS noise
  // adaptation loosened GNSS to a correlated error of metres; k_speed then ran to -4e-4 per
  // (m/s)^2 (-100 % at 50 m/s) and c_RL to +45 mm, and the guard undid the adaptation. With the
  // slip's load terms the residuals match the configured noise and nothing is adapted; either
  // way the model must stay a tyre.
  std::optional<sim::Scenario> hockenheim = hockenheim_scenario();
  if (!hockenheim) GTEST_SKIP() << "shared data absent: " << kHockenheimTrack;
  sim::Scenario& scenario = *hockenheim;
  scenario.dynamics.drivetrain = sim::Drivetrain::kFront;
  // Built on the simulator's force in steps (actuator_time_constant_s 0, before 2026-12-05). With
  // the lag the regression terms land c_RL +39.7 mm off at a sigma of ~40 mm (docs/simulator.md).
  scenario.dynamics.actuator_time_constant_s = 0.0;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive);
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kExtended;
  const BatchSummary result = calibrate_batch(log, options);
  const auto states = driving_states(log, result.estimate);
  double worst = 0.0;
  for (const DrivingState& state : states)
    worst = std::max(worst,
                     std::abs(tyre_factor(result.tyre_model, state, RearWheel::kLeft, kBody) - 1));
  // The truth's own factor reaches ~3 % under the circuit's hardest braking; the run-away
  // reached -100 %.
  EXPECT_LT(worst, 0.1) << result.full_report();
  EXPECT_TRUE(result.gnss_noise.reverted || !result.gnss_noise.adapted) << result.full_report();
  EXPECT_LT(result.estimate.circumference_rl_m - drive.true_params.circumference_rl_m, 0.02);
}

TEST(TyreModelBatch, AnAdaptedNoiseThatRanAwayLeavesTheFirstEstimateAsItWas) {
  // The racing line, seed 7, regression terms: the GNSS noise adapted to a correlated error of
  // 10 m carried c_RL to 0.44 m, and the first estimate was to stand. Solved again from there it
  // ran on to -9e16 m with terms of 1e38; solved again from the first estimate it walked to
  // +24 mm of nominal. Put back as it was, it is the first fit's, finite and in the band.
  std::optional<sim::Scenario> scenario = raceline_scenario(7);
  if (!scenario) GTEST_SKIP() << "shared data absent: " << kHockenheimRaceline;
  // Built on the simulator's force in steps (actuator_time_constant_s 0, before 2026-12-05): with
  // the lag the noise adaptation is not undone on seed 7.
  scenario->dynamics.actuator_time_constant_s = 0.0;
  const Log log = simulated_log(sim::simulate(*scenario));
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kExtended;
  options.max_sigma_circumference_m = 0.01;
  // The reverted estimate looks for no mounting; without the adaptation the fit would go on to
  // look (since the batch's heading is a local quadratic its residuals here are 1.9 times the
  // fixes' noise and it fits an antenna, refused as before): the first fit is what is compared.
  options.detect_mounting = false;
  const BatchSummary adapted = calibrate_batch(log, options);
  ASSERT_TRUE(adapted.gnss_noise.reverted) << adapted.full_report();
  EXPECT_TRUE(std::isfinite(adapted.sigma_rl_m())) << adapted.full_report();
  options.adapt_gnss_noise = false;
  const BatchSummary first = calibrate_batch(log, options);
  EXPECT_DOUBLE_EQ(adapted.estimate.circumference_rl_m, first.estimate.circumference_rl_m);
  EXPECT_DOUBLE_EQ(adapted.estimate.circumference_rr_m, first.estimate.circumference_rr_m);
}

TEST(TyreModelBatch, AutoFitsTyresSofterThanTheCarsValueWithThePhysicalTerms) {
  // 3 laps of Hockenheim, rear-driven, the grip-sharing driver, tyres softer than the car's value
  // (slip stiffness 14 per unit load; tyre_car_prior.hpp's 20). Until the slip divided the
  // circumference (2026-11-30, evening) the physical fit's drive slip came out at a car's 3.4 %
  // of slip at the log's RMS state, judged no tyre, and auto fell back to the regression terms
  // (c_RL -8.6 mm at sigma 7.9 mm, dead reckoning 543 m). A slip coefficient is judged as what it
  // is, the axle's share over the slip stiffness (at most 0.1: 10 per unit load); the physical
  // terms stand, the drive slip at the truth's 1 / 14.
  std::optional<sim::Scenario> hockenheim = hockenheim_scenario();
  if (!hockenheim) GTEST_SKIP() << "shared data absent: " << kHockenheimTrack;
  sim::Scenario& scenario = *hockenheim;
  scenario.driver.friction_ellipse = true;
  scenario.driver.max_power_wpkg = 80.0;
  scenario.dynamics.slip_stiffness_per_load = 14.0;
  scenario.vehicle.wear_rl_mm = 1.5;
  scenario.vehicle.wear_rr_mm = 1.0;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive);
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kAuto;
  // The circumferences' sigma is ~10 mm, nearly all the body's uncertainty (its cornering
  // stiffness among it since 2026-12-05): the estimate is scored against the truth below.
  options.max_sigma_circumference_m = 0.012;
  const BatchSummary result = calibrate_batch(log, options);
  ASSERT_EQ(result.tyre_selection.chosen, "physical") << result.full_report();
  EXPECT_TRUE(result.tyre_selection.candidates.at(0).tyre);
  EXPECT_NEAR(result.tyre_model.k_drive_slip, 1.0 / 14.0, 0.01) << result.full_report();
  EXPECT_TRUE(result.usable()) << result.full_report();
  for (const auto& [estimate, truth] :
       {std::pair{result.estimate.circumference_rl_m, drive.true_params.circumference_rl_m},
        std::pair{result.estimate.circumference_rr_m, drive.true_params.circumference_rr_m}}) {
    EXPECT_LT(std::abs(estimate - truth), 3.0 * result.sigma_rl_m()) << result.full_report();
    EXPECT_LT(std::abs(estimate - truth), 0.002) << result.full_report();
  }
  EXPECT_LT(result.after.mean_position_m, 50.0) << result.full_report();
}

TEST(TyreModelBatch, AFitThatItsResidualsRejectCarriesTheirScatterInItsSigma) {
  // 3 laps of Hockenheim's racing line, rear-driven, a driver who fishtails out of the corners.
  // The two-wheel model cannot follow the inner wheel's spin: its odometry residuals are many
  // times as wide as their noise, and their width is in the sigma: inside it, and refused even
  // at a 10 mm limit, the misfit named. Likewise for a method that is not the batch. (auto's
  // regression terms gave c_RL +20.2 mm at sigma 3.0 mm here before the misfit counted; since
  // 2026-11-30 the physical terms explain the log, chi2/dof 1.25.)
  const std::optional<sim::Scenario> scenario = raceline_scenario(1);
  if (!scenario) GTEST_SKIP() << "shared data absent: " << kHockenheimRaceline;
  const sim::SimulatedDrive drive = sim::simulate(*scenario);
  const Log log = simulated_log(drive);
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  options.tyre_model = TyreModelChoice::kNone;
  const BatchSummary result = calibrate_batch(log, options);
  EXPECT_GT(result.model_adequacy.chi2_per_dof, 9.0) << result.full_report();
  EXPECT_DOUBLE_EQ(result.misfit_sigma_scale, std::sqrt(result.model_adequacy.chi2_per_dof));
  expect_inside_3_sigma(result, drive.true_params, result.full_report());
  EXPECT_FALSE(result.usable()) << result.full_report();
  EXPECT_NE(result.full_report().find("every sigma widened"), std::string::npos);
  EXPECT_NE(result.message.find("misfit"), std::string::npos) << result.message;
  // auto's physical terms explain it, their estimate inside its sigma.
  options.tyre_model = TyreModelChoice::kAuto;
  const BatchSummary chosen = calibrate_batch(log, options);
  EXPECT_EQ(chosen.tyre_selection.chosen, "physical") << chosen.full_report();
  EXPECT_LT(chosen.model_adequacy.chi2_per_dof, 2.0) << chosen.full_report();
  expect_inside_3_sigma(chosen, drive.true_params, chosen.full_report());

  // The iterative method fits the same two-wheel model; the judge's plain batch fit of the log
  // shows its residuals 24 times as wide as their noise (-40.8 mm at sigma 1.5 mm before).
  const IterativeSummary iterative = calibrate_iterative(log);
  ASSERT_TRUE(iterative.usable()) << iterative.full_report();
  EXPECT_GT(iterative.misfit_sigma_scale, 3.0) << iterative.full_report();
  EXPECT_LT(std::abs(iterative.estimate.circumference_rl_m - drive.true_params.circumference_rl_m),
            3.0 * iterative.sigma_rl_m())
      << iterative.full_report();
  EXPECT_NE(iterative.full_report().find("every sigma widened"), std::string::npos);
}

TEST(TyreModelBatch, GentleSegmentsFitOnlyTheOdometryInsideTheLimits) {
  // Ideal drive with worn tyres: cutting the rough intervals costs information (a wider sigma)
  // but must not bias the estimate.
  sim::Scenario scenario = load_scenario("urban");
  scenario.ideal = true;
  scenario.gnss.sigma_m = 0.5;
  scenario.vehicle.wear_rl_mm = 1.5;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive);
  const BatchSummary all = calibrate_batch(log);
  BatchOptions gentle;
  gentle.gentle_max_longitudinal_mps2 = 1.0;
  gentle.gentle_max_lateral_mps2 = 2.0;
  const BatchSummary part = calibrate_batch(log, gentle);
  EXPECT_TRUE(part.gentle_limits);
  EXPECT_FALSE(all.gentle_limits);
  EXPECT_EQ(all.odometry_intervals_used, all.odometry_intervals);
  EXPECT_LT(part.odometry_intervals_used, part.odometry_intervals);
  EXPECT_GT(part.odometry_intervals_used, 0u);
  EXPECT_GT(part.sigma_rl_m(), all.sigma_rl_m());
  EXPECT_LT(std::abs(part.estimate.circumference_rl_m - drive.true_params.circumference_rl_m),
            3.0 * part.sigma_rl_m());
  EXPECT_NE(part.full_report().find("inside the limits feed the odometry"), std::string::npos);
}

}  // namespace
}  // namespace odocal
