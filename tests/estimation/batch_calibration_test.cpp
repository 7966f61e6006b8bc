// The batch maximum-likelihood calibration on simulated drives: wear recovered within the
// reported uncertainty, which is the Cramér–Rao bound's, optional unknowns, robustness to GNSS
// outliers. Labelled slow.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "experiments/drifting_gnss.hpp"
#include "experiments/worn_circuit.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/estimation/cramer_rao.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {
sim::Scenario ideal_lap() { return experiments::worn_ideal_circuit(1, 1); }

void expect_within_3_sigma(const BatchSummary& result, const OdometryParams& truth) {
  const double error_rl = result.estimate.circumference_rl_m - truth.circumference_rl_m;
  const double error_rr = result.estimate.circumference_rr_m - truth.circumference_rr_m;
  EXPECT_LT(std::abs(error_rl), 3.0 * std::sqrt(result.covariance(0, 0)));
  EXPECT_LT(std::abs(error_rr), 3.0 * std::sqrt(result.covariance(1, 1)));
  EXPECT_LT(std::abs(error_rl), 5e-4);
  EXPECT_LT(std::abs(error_rr), 5e-4);
}

TEST(BatchCalibration, RecoversTheWearWithinItsReportedUncertainty) {
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    sim::Scenario scenario = ideal_lap();
    scenario.seeds.noise = seed;
    const sim::SimulatedDrive drive = sim::simulate(scenario);
    const BatchSummary result = calibrate_batch(simulated_log(drive));
    SCOPED_TRACE(result.message);
    EXPECT_EQ(result.termination, Termination::kConverged);
    EXPECT_TRUE(result.usable());
    EXPECT_NE(result.message.find("CONVERGENCE"), std::string::npos);
    expect_within_3_sigma(result, drive.true_params);
    EXPECT_EQ(result.identifiability, "every requested parameter identified");
    EXPECT_LT(result.after.mean_position_m, result.before.mean_position_m);
    // The model fits: its residuals are inside their noise, and nothing is widened.
    EXPECT_LT(result.model_adequacy.chi2_per_dof, 1.0);
    EXPECT_EQ(result.misfit_sigma_scale, 1.0);
  }
}

TEST(BatchCalibration, ReportsTheUncertaintyOfTheQuantisationLimitedBound) {
  // Independent truth: the Cramér–Rao bound of the same log with the encoders' quantisation as
  // count noise. With the wheel noise of an ideal drive (no slip), the batch's reported sigma is
  // that bound: it neither claims more than the data hold nor leaves information unused.
  sim::Scenario scenario = ideal_lap();
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive, true);
  BatchOptions options;
  options.slip_sigma_m_per_sqrt_m = options.lateral_sigma_m_per_sqrt_m = 1e-6;
  options.track_width_uncertainty = 0.0;  // the bound's: the track known
  const BatchSummary result = calibrate_batch(log, options);
  const CramerRaoBound bound = circumference_cramer_rao_bound(
      log, drive.true_params, log.truth->pose.front(),
      {.gnss_sigma_m = scenario.gnss.sigma_m,
       .heading_sigma_rad = scenario.heading.sigma_rad,
       .quantisation_sigma_rev = encoder_quantisation_sigma_rev(log)});
  const double reported_rl = std::sqrt(result.covariance(0, 0));
  const double reported_rr = std::sqrt(result.covariance(1, 1));
  EXPECT_GT(reported_rl, 0.95 * bound.sigma_c_rl_m);
  EXPECT_LT(reported_rl, 1.25 * bound.sigma_c_rl_m);
  EXPECT_GT(reported_rr, 0.95 * bound.sigma_c_rr_m);
  EXPECT_LT(reported_rr, 1.25 * bound.sigma_c_rr_m);
  expect_within_3_sigma(result, drive.true_params);
}

TEST(BatchCalibration, EstimatesTrackWidthGyroBiasAndLatencyWhenAsked) {
  sim::Scenario scenario = ideal_lap();
  scenario.imu.gyro_bias_radps = 0.01;
  scenario.gnss.latency_s = 0.1;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  Log log = simulated_log(drive);
  log.vehicle.track_width_m = 1.55;  // vehicle.yaml is 5 cm off
  BatchOptions options;
  options.estimate_track_width = true;
  options.estimate_gyro_bias = true;
  options.estimate_latency = true;
  const BatchSummary result = calibrate_batch(log, options);
  const auto find = [&](const std::string& name) {
    for (const EstimatedParameter& p : result.parameters)
      if (p.name == name) return p;
    ADD_FAILURE() << name;
    return EstimatedParameter{};
  };
  const EstimatedParameter track = find("track_width_m");
  EXPECT_TRUE(track.identified) << track.verdict;
  EXPECT_LT(std::abs(track.value - 1.6), 3.0 * track.sigma);
  const EstimatedParameter gyro = find("gyro_bias_radps");
  EXPECT_LT(std::abs(gyro.value - 0.01), 3.0 * gyro.sigma);
  const EstimatedParameter latency = find("latency_s");
  EXPECT_LT(std::abs(latency.value - 0.1), 3.0 * latency.sigma + 1e-3);
  EXPECT_FALSE(find("heading_bias_rad").estimated);
  expect_within_3_sigma(result, drive.true_params);
}

// The gyro's turn over a keyframe interval is the trapezoid of its samples. Held from each sample
// to the next, it lagged by half a sample (10 ms at 50 Hz), which the urban drive's tight turns
// read as circumferences 3-6 mm short, the more so the shorter the keyframes (seed 2, physical
// terms, keyframes of 0.5 / 1 / 2 s: -5.6 / -4.3 / -3.1 mm at a sigma of 2.6 mm).
TEST(BatchCalibration, TheGyrosTurnDoesNotLagSoTheKeyframesDoNotMoveTheAnswer) {
  sim::Scenario scenario = load_scenario("urban");
  scenario.seeds.noise = scenario.seeds.trajectory = 2;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive);
  std::vector<double> errors;
  for (const double interval : {0.5, 2.0}) {
    BatchOptions options;
    options.tyre_model = TyreModelChoice::kPhysical;
    options.max_sigma_circumference_m = 0.05;
    options.keyframe_interval_s = interval;
    const BatchSummary s = calibrate_batch(log, options);
    errors.push_back(s.estimate.circumference_rl_m - drive.true_params.circumference_rl_m);
    EXPECT_LT(std::abs(errors.back()), 0.5 * s.sigma_rl_m()) << s.full_report();
  }
  EXPECT_NEAR(errors[0], errors[1], 5e-4);
}

TEST(BatchCalibration, RobustLossKeepsGnssOutliersOut) {
  // Multipath in one place: 2 % of the fixes, in one stretch, 30 m off to the east. The squared
  // loss bends the trajectory towards them; the robust losses mostly ignore them.
  const sim::SimulatedDrive drive = sim::simulate(ideal_lap());
  const Log clean = simulated_log(drive);
  Log log = clean;
  const std::size_t first = log.gnss.size() / 3, count = log.gnss.size() / 50;
  for (std::size_t j = first; j < first + count; ++j) log.gnss.x_m[j] += 30.0;
  const BatchSummary reference = calibrate_batch(clean);
  const auto moved = [&](const BatchOptions& options) {
    const BatchSummary r = calibrate_batch(log, options);
    return std::hypot(r.estimate.circumference_rl_m - reference.estimate.circumference_rl_m,
                      r.estimate.circumference_rr_m - reference.estimate.circumference_rr_m);
  };
  const double cauchy = moved({});
  BatchOptions options;
  options.gnss_loss = RobustLoss::kNone;
  const double squared = moved(options);
  options.gnss_loss = RobustLoss::kHuber;
  const double huber = moved(options);
  EXPECT_LT(cauchy, 0.75 * std::sqrt(reference.covariance(0, 0)));
  EXPECT_GT(squared, 3.0 * cauchy);
  EXPECT_LT(huber, squared);
}

TEST(BatchCalibrationOutcome, CircumferencesLooserThanRequiredAreNotIdentifiedAndNotUsable) {
  const sim::SimulatedDrive drive = sim::simulate(ideal_lap());
  BatchOptions options;
  options.max_sigma_circumference_m = 1e-7;  // far below what one lap can give
  const BatchSummary result = calibrate_batch(simulated_log(drive), options);
  EXPECT_EQ(result.termination, Termination::kNotIdentifiable);
  EXPECT_FALSE(result.usable());
  // One line: both wheels' sigma against the limit, not every parameter's verdict.
  EXPECT_NE(result.message.find("circumference_rl_m 1-sigma"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("(max_sigma_circumference_m 0.0001 mm)"), std::string::npos)
      << result.message;
  EXPECT_NE(result.identifiability.find("circumference_rl_m: "), std::string::npos);
  EXPECT_FALSE(result.parameters[0].identified);
  // The numbers are still reported, for the record.
  EXPECT_GT(result.sigma_rl_m(), 1e-7);
  EXPECT_NE(result.estimate.circumference_rl_m, result.nominal.circumference_rl_m);
}

TEST(BatchCalibrationNoise, AWronglyConfiguredGnssNoiseIsEstimatedAndTheSigmaCoversTheError) {
  // The GNSS drifts (Gauss-Markov, 1.5 m over 30 s) while the configuration claims 0.1 m white.
  const auto [scenario, drive, log, claimed] =
      experiments::drifting_gnss_drive(ideal_lap(), 1.5, 30.0);
  const BatchSummary adapted = calibrate_batch(log, {}, claimed);
  BatchOptions fixed;
  fixed.adapt_gnss_noise = false;
  // The regression terms, which auto chooses here: they take up some of the drift. Unjudged:
  // judged (and under auto) their sigma also carries their gap to the physical terms' fit,
  // 3.7 mm since the physical slip divides the circumference (2026-11-30), which covers this
  // error for a reason that is not the noise; the plain model's misfit widens its sigma past it
  // as well.
  fixed.tyre_model = TyreModelChoice::kExtended;
  CalibrationOptions claimed_unjudged = claimed;
  claimed_unjudged.judge_model_adequacy = false;
  const BatchSummary configured = calibrate_batch(log, fixed, claimed_unjudged);
  SCOPED_TRACE(adapted.full_report());
  ASSERT_TRUE(adapted.gnss_noise.adapted);
  // The residuals show part of the drift; the model keeps their random-walk intensity over at
  // least a tenth of the log, which lands near the truth.
  EXPECT_GT(adapted.gnss_noise.gauss_markov_sigma_m, 0.3);
  EXPECT_NEAR(adapted.gnss_noise.model_gauss_markov_sigma_m, 1.5, 0.6);
  EXPECT_GT(adapted.gnss_noise.model_gauss_markov_tau_s, 10.0);
  EXPECT_LT(adapted.gnss_noise.model_gauss_markov_tau_s, 90.0);
  EXPECT_GT(adapted.gnss_noise.sigma_inflation, 2.0);
  // One lap under such GNSS cannot pin the circumferences to max_sigma_circumference_m (1 mm):
  // said so, not hidden behind a small sigma.
  EXPECT_EQ(adapted.termination, Termination::kNotIdentifiable);
  EXPECT_NE(adapted.full_report().find("where 0.1 m was configured"), std::string::npos);
  const double error_rl =
      adapted.estimate.circumference_rl_m - drive.true_params.circumference_rl_m;
  EXPECT_LT(std::abs(error_rl), 3.0 * adapted.sigma_rl_m());
  // Without the adaptation the sigma is far too small for the same error (the reason it exists).
  const double error_fixed =
      configured.estimate.circumference_rl_m - drive.true_params.circumference_rl_m;
  EXPECT_GT(std::abs(error_fixed), 3.0 * configured.sigma_rl_m()) << configured.full_report();
}

TEST(BatchCalibrationNoise, ADriftTheFirstFitHidesInItsTrajectoryIsModelledAtItsSize) {
  // 2 m over 60 s on three laps (bench/honest_sigma.cpp's run 33): trusting 0.1 m, the first fit
  // follows most of the drift, its residuals a third of a metre. The modelled error must reach
  // the drift's size, not stop at a few times what the first fit showed (capped there, the
  // model was 0.99 m and the error +2.35 mm at a sigma of 0.46 mm). The track is taken as exact,
  // as it was then, so that the drift's model alone carries the sigma: by default the track of
  // this log, which the two-wheel model explains, is fitted under its prior, and the fit is
  // +2.72 mm off at a sigma of 0.89 mm (3.05 sigma; the worst of bench/honest_sigma.cpp's 80
  // errors, docs/batch-calibration.md, "The track under its prior").
  sim::Scenario scenario = ideal_lap();
  scenario.route.laps = 3;
  scenario.seeds.noise = 33;
  const auto [drifting, drive, log, claimed] =
      experiments::drifting_gnss_drive(scenario, 2.0, 60.0);
  BatchOptions track_exact;
  track_exact.track_width_uncertainty = 0.0;
  const BatchSummary adapted = calibrate_batch(log, track_exact, claimed);
  SCOPED_TRACE(adapted.full_report());
  ASSERT_TRUE(adapted.gnss_noise.adapted);
  EXPECT_NEAR(adapted.gnss_noise.model_gauss_markov_sigma_m, 2.0, 0.5);
  const double error_rl =
      adapted.estimate.circumference_rl_m - drive.true_params.circumference_rl_m;
  EXPECT_LT(std::abs(error_rl), 3.0 * adapted.sigma_rl_m());
}

// The built-in urban drive (2 km in 300 s), kinematic, its receiver's white 3 m at 50 Hz on a
// Gauss-Markov error of 2 m over 60 s; gnss.csv's sigma_m carries the total.
sim::SimulatedDrive urban_drive_under_a_wandering_receiver() {
  sim::Scenario scenario = load_scenario("urban");
  scenario.ideal = true;
  scenario.gnss.gauss_markov_sigma_m = 2.0;
  scenario.gnss.gauss_markov_tau_s = 60.0;
  return sim::simulate(scenario);
}

double error_in_sigmas(const BatchSummary& result, const sim::SimulatedDrive& drive) {
  return std::abs(result.estimate.circumference_rl_m - drive.true_params.circumference_rl_m) /
         result.sigma_rl_m();
}

TEST(BatchCalibrationNoise, AStatedCorrelatedErrorSmallerThanTheResidualsShowIsWidened) {
  // 0.5 m stated: the adaptation, once off under any stated correlated error, now models what
  // the residuals show, and never less than what was stated (docs/batch-calibration.md).
  const sim::SimulatedDrive drive = urban_drive_under_a_wandering_receiver();
  const Log log = simulated_log(drive);
  BatchOptions batch;
  batch.tyre_model = TyreModelChoice::kNone;
  batch.gnss_gauss_markov_sigma_m = 0.5;
  const BatchSummary adapted = calibrate_batch(log, batch);
  batch.adapt_gnss_noise = false;
  const BatchSummary stated = calibrate_batch(log, batch);
  SCOPED_TRACE(adapted.full_report());
  ASSERT_TRUE(adapted.gnss_noise.adapted);
  EXPECT_GT(adapted.gnss_noise.model_gauss_markov_sigma_m, 1.0);
  EXPECT_NE(adapted.full_report().find("and a correlated"), std::string::npos);
  EXPECT_LT(error_in_sigmas(adapted, drive), 3.0);
  EXPECT_GT(error_in_sigmas(stated, drive), 3.0);  // what the stated error alone gave
}

TEST(BatchCalibrationNoise, AStatedCorrelatedErrorAsLargeAsTheTruthIsLeftAlone) {
  const sim::SimulatedDrive drive = urban_drive_under_a_wandering_receiver();
  BatchOptions batch;
  batch.tyre_model = TyreModelChoice::kNone;
  batch.gnss_gauss_markov_sigma_m = 2.0;
  const BatchSummary result = calibrate_batch(simulated_log(drive), batch);
  SCOPED_TRACE(result.full_report());
  EXPECT_FALSE(result.gnss_noise.adapted);
  EXPECT_LT(error_in_sigmas(result, drive), 3.0);
}

TEST(BatchCalibrationNoise, ACorrectlyConfiguredWhiteNoiseIsLeftAlone) {
  const sim::SimulatedDrive drive = sim::simulate(ideal_lap());
  const BatchSummary result = calibrate_batch(simulated_log(drive));
  EXPECT_FALSE(result.gnss_noise.adapted);
  EXPECT_NEAR(result.gnss_noise.residual_sigma_m, 3.0, 0.3);
  EXPECT_EQ(result.gnss_noise.gauss_markov_sigma_m, 0.0);
}

}  // namespace
}  // namespace odocal
