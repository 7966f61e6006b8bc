// A lag between the GNSS and the wheels that the configuration does not estimate: the tyre terms
// read it as slip, and BatchOptions::detect_latency finds it (docs/batch-calibration.md, "A
// latency the log shows").

#include "estimation/latency_detection.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/estimation/log_window.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

// One lap of the realistic circuit, front-driven, a receiver with a Doppler column whose fixes
// are stamped `latency_s` after the position they report.
sim::SimulatedDrive lap_with_gnss_latency(double latency_s) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.route.laps = 1;
  scenario.dynamics.drivetrain = Drivetrain::kFront;
  scenario.vehicle.wear_rl_mm = 1.5;
  scenario.vehicle.wear_rr_mm = 1.0;
  scenario.gnss.speed_sigma_mps = 0.05;
  scenario.gnss.latency_s = latency_s;
  return sim::simulate(scenario);
}

TEST(LatencyDetection, ATyreFitThatReadsALagAsSlipIsFittedAgainWithTheLatency) {
  const sim::SimulatedDrive drive = lap_with_gnss_latency(0.09);
  const Log log = simulated_log(drive);
  const double truth_m = drive.true_params.circumference_rl_m;
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;

  // Not looked for, the physical terms take the lag for slip: ~10 mm off, beyond 2 of their own
  // sigma (their witness, the regression terms, disagrees and widens it by the gap), and their
  // Doppler residual still follows a_x.
  options.detect_latency = false;
  const BatchSummary blind = calibrate_batch(log, options);
  ASSERT_EQ(blind.tyre_selection.chosen, "physical") << blind.full_report();
  const double own_sigma_m = std::sqrt(blind.sigma_rl_m() * blind.sigma_rl_m() -
                                       blind.model_spread_m[0] * blind.model_spread_m[0]);
  EXPECT_GT(std::abs(blind.estimate.circumference_rl_m - truth_m), 2.0 * own_sigma_m)
      << blind.full_report();
  EXPECT_FALSE(blind.latency_detection.has_value());

  options.detect_latency = true;
  const BatchSummary found = calibrate_batch(log, options);
  ASSERT_TRUE(found.latency_detection.has_value()) << found.full_report();
  const BatchSummary::LatencyDetection& detection = *found.latency_detection;
  EXPECT_TRUE(detection.taken);
  EXPECT_EQ(detection.signature.quantity, "longitudinal acceleration");
  EXPECT_NEAR(detection.latency_s, 0.09, 3.0 * detection.sigma_s + 0.005);
  EXPECT_DOUBLE_EQ(detection.circumference_without_m[0], blind.estimate.circumference_rl_m);
  EXPECT_LT(std::abs(found.estimate.circumference_rl_m - truth_m), 3.0 * found.sigma_rl_m())
      << found.full_report();
  EXPECT_LT(std::abs(found.estimate.circumference_rl_m - truth_m), 0.002);
  EXPECT_NE(found.full_report().find("latency      the fit without it left the"), std::string::npos)
      << found.full_report();
  // As if it had been asked for.
  options.estimate_latency = true;
  const BatchSummary asked = calibrate_batch(log, options);
  EXPECT_DOUBLE_EQ(asked.estimate.circumference_rl_m, found.estimate.circumference_rl_m);
  EXPECT_FALSE(asked.latency_detection.has_value());
}

TEST(LatencyDetection, ALogWithoutALagIsNotFittedAgain) {
  const Log log = simulated_log(lap_with_gnss_latency(0.0));
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  const BatchSummary summary = calibrate_batch(log, options);
  EXPECT_EQ(summary.tyre_selection.chosen, "physical") << summary.full_report();
  EXPECT_FALSE(summary.latency_detection.has_value()) << summary.full_report();
}

// The built-in urban drive (rear-driven) with a Doppler column whose fixes are stamped
// `latency_s` late; heading.csv read `heading_bias_rad` off.
sim::Scenario urban_with_gnss_latency(double latency_s, std::uint64_t seed,
                                      double heading_bias_rad = 0.0) {
  sim::Scenario scenario = load_scenario("urban");
  scenario.seeds.noise = scenario.seeds.trajectory = seed;
  scenario.gnss.speed_sigma_mps = 0.05;
  scenario.gnss.latency_s = latency_s;
  scenario.heading.bias_rad = heading_bias_rad;
  return scenario;
}

bool estimated(const BatchSummary& s, const std::string& name) {
  for (const EstimatedParameter& p : s.parameters)
    if (p.name == name) return p.estimated;
  return false;
}

void expect_a_usable_answer_that_covers_the_truth(const BatchSummary& s,
                                                  const sim::SimulatedDrive& drive) {
  EXPECT_EQ(s.termination, Termination::kConverged) << s.full_report();
  EXPECT_LT(std::abs(s.estimate.circumference_rl_m - drive.true_params.circumference_rl_m),
            3.0 * s.sigma_rl_m())
      << s.full_report();
}

// A lag along the track leaves the fixes behind the fitted path, as an antenna behind the axle
// does; the mounting is looked for first and found (0.63 m behind at 13 sigma), but beside the
// latency it is nothing, and the log is calibrated with the latency alone.
TEST(LatencyDetection, ALagThatShowedAsAnAntennaBehindTheAxleIsFittedWithTheLatencyAlone) {
  const sim::SimulatedDrive drive = sim::simulate(urban_with_gnss_latency(0.14, 1));
  const BatchSummary s = calibrate_batch(simulated_log(drive));
  const std::string report = s.full_report();
  ASSERT_TRUE(s.mounting_detection.has_value()) << report;
  ASSERT_TRUE(s.latency_detection.has_value()) << report;
  EXPECT_TRUE(s.mounting_detection->lever_arm);
  EXPECT_TRUE(s.mounting_detection->explained_by_latency) << report;
  EXPECT_FALSE(s.mounting_detection->taken);
  EXPECT_LT(s.mounting_detection->lever_arm_m[0], -0.3) << report;  // what the first fit took
  EXPECT_FALSE(estimated(s, "lever_arm_x_m")) << report;
  EXPECT_TRUE(s.latency_detection->taken);
  EXPECT_NEAR(s.latency_detection->latency_s, 0.14, 3.0 * s.latency_detection->sigma_s + 0.005);
  // Against the fit with neither.
  EXPECT_DOUBLE_EQ(s.latency_detection->circumference_without_m[0],
                   s.mounting_detection->circumference_without_m[0]);
  EXPECT_NE(report.find("the lag showed as it, kept without"), std::string::npos) << report;
  expect_a_usable_answer_that_covers_the_truth(s, drive);
}

// heading.csv 4 degrees off and the fixes 145 ms late: with the heading found, the physical terms
// are no tyre while the lag is in, and the regression terms take the lag's a_x dependence; what it
// leaves is the Doppler speed's noise, 5.5 times the configured.
TEST(LatencyDetection, ALagThatTheRegressionTermsHideIsLookedForByTheDopplerNoise) {
  const sim::SimulatedDrive drive = sim::simulate(urban_with_gnss_latency(0.145, 11, -0.076));
  const BatchSummary s = calibrate_batch(simulated_log(drive));
  const std::string report = s.full_report();
  ASSERT_TRUE(s.latency_detection.has_value()) << report;
  EXPECT_TRUE(s.latency_detection->by_doppler_noise) << report;
  EXPECT_GT(s.latency_detection->doppler_sigma_scale, 2.0);
  EXPECT_TRUE(s.latency_detection->taken) << report;
  EXPECT_NEAR(s.latency_detection->latency_s, 0.145, 3.0 * s.latency_detection->sigma_s + 0.005);
  EXPECT_TRUE(estimated(s, "heading_bias_rad")) << report;
  EXPECT_NE(report.find("left the Doppler speed's noise"), std::string::npos) << report;
  expect_a_usable_answer_that_covers_the_truth(s, drive);
}

// Stated (BatchOptions::latency_s), a latency is the same log as one whose stamps were put right:
// the Doppler speed's window is shifted by it. Taken to first order in the whole 143 ms, the
// regression terms (fitted with an exact Doppler speed, the drive at seed 19) put the
// circumference at rest 4.7 mm from the unlagged log's. Both logs are cut to the lagged one's
// first fix: the keyframes start at the first fix, and the regression terms' circumference moves
// by up to 1.2 mm (at a sigma of 2-3 mm) when their grid moves by the 0.16 s that the lag takes
// off the fixes' start, where the same grid puts the two fits within 0.03 mm (seeds 1-4, 19;
// 14 mm apart with the latency not stated).
TEST(LatencyDetection, AStatedLatencyFitsAsTheSameLogWithoutTheLag) {
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kExtended;
  options.gnss_speed_sigma_mps = 0.05;
  options.max_sigma_circumference_m = 0.05;
  options.detect_latency = options.detect_mounting = false;
  sim::Scenario lagged = urban_with_gnss_latency(0.143, 19);
  lagged.gnss.speed_sigma_mps = 0.0;
  sim::Scenario unlagged = lagged;
  unlagged.gnss.latency_s = 0.0;
  const Log lagged_log = simulated_log(sim::simulate(lagged));
  const Log unlagged_log = simulated_log(sim::simulate(unlagged));
  const double from_s = lagged_log.gnss.t_s.front();
  const double to_s = unlagged_log.gnss.t_s.back();
  const BatchSummary clean = calibrate_batch(slice_log(unlagged_log, from_s, to_s), options);
  options.latency_s = 0.143;
  const BatchSummary stated = calibrate_batch(slice_log(lagged_log, from_s, to_s), options);
  EXPECT_NEAR(stated.estimate.circumference_rl_m, clean.estimate.circumference_rl_m, 1e-4)
      << stated.full_report() << clean.full_report();
  EXPECT_FALSE(estimated(stated, "latency_s"));
}

// The built-in urban drive with fixes of `sigma_m` white noise (RTK: 2 cm), stamped `latency_s`
// late, no Doppler column.
sim::Scenario urban_with_precise_fixes(double sigma_m, double latency_s) {
  sim::Scenario scenario = load_scenario("urban");
  scenario.gnss.sigma_m = sigma_m;
  scenario.gnss.latency_s = latency_s;
  return scenario;
}

// RTK fixes 150 ms late are 0.95 m RMS off the path: the noise adaptation took that for a
// correlated error of the receiver (sigma x35, the answer -12.3 mm at a sigma of 22.7 mm), the fit
// was plain and its residuals counted no dependence. Their noise is the sign.
TEST(LatencyDetection, ALagInPreciseFixesIsLookedForByTheirNoise) {
  const sim::SimulatedDrive drive = sim::simulate(urban_with_precise_fixes(0.02, 0.15));
  const BatchSummary s = calibrate_batch(simulated_log(drive));
  const std::string report = s.full_report();
  ASSERT_TRUE(s.latency_detection.has_value()) << report;
  EXPECT_TRUE(s.latency_detection->by_gnss_noise);
  EXPECT_GT(s.latency_detection->gnss_sigma_scale, 10.0);
  EXPECT_LT(s.latency_detection->gnss_sigma_scale_with, 1.2);
  EXPECT_TRUE(s.latency_detection->taken);
  EXPECT_NEAR(s.latency_detection->latency_s, 0.15, 3.0 * s.latency_detection->sigma_s + 0.001);
  EXPECT_FALSE(s.gnss_noise.adapted) << report;
  EXPECT_NE(report.find("left the GNSS fixes' residuals"), std::string::npos) << report;
  expect_a_usable_answer_that_covers_the_truth(s, drive);
}

// The drive calibrated with the defaults, where a latency and a lever arm beside it are both
// expected to be taken: the summary, its report, and the mounting detection checked present.
struct BothFound {
  BatchSummary summary;
  std::string report;
};
BothFound calibrated_with_lag_and_mounting(const sim::SimulatedDrive& drive) {
  BothFound found{calibrate_batch(simulated_log(drive)), {}};
  found.report = found.summary.full_report();
  EXPECT_TRUE(found.summary.latency_detection.has_value()) << found.report;
  EXPECT_TRUE(found.summary.mounting_detection.has_value()) << found.report;
  if (found.summary.latency_detection) {
    EXPECT_TRUE(found.summary.latency_detection->taken) << found.report;
  }
  return found;
}

// RTK fixes 130 ms late from an antenna 0.27 m behind and 0.39 m right of the axle's centre: the
// noise adaptation hid the antenna from the residuals' means, and the latency alone (near 170 ms)
// left the fixes 1.4 times their noise. With the lever arm estimated beside it, both are found
// and the fixes are as configured.
TEST(LatencyDetection, AnAntennaOffTheCentreBesideALagInPreciseFixesIsFoundWithIt) {
  sim::Scenario scenario = urban_with_precise_fixes(0.02, 0.13);
  scenario.gnss.lever_arm_x_m = -0.27;
  scenario.gnss.lever_arm_y_m = -0.39;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const auto [s, report] = calibrated_with_lag_and_mounting(drive);
  ASSERT_TRUE(s.latency_detection && s.mounting_detection);
  EXPECT_NEAR(s.latency_detection->latency_s, 0.13, 3.0 * s.latency_detection->sigma_s + 0.001);
  const BatchSummary::MountingDetection& m = *s.mounting_detection;
  EXPECT_TRUE(m.found_beside_latency && m.taken) << report;
  EXPECT_GT(m.gnss_sigma_scale_without, batch::kLagGnssExplained);
  EXPECT_LT(m.gnss_sigma_scale_with, batch::kLagGnssExplained);
  EXPECT_NEAR(m.lever_arm_m[0], -0.27, 3.0 * m.lever_arm_sigma_m[0] + 0.01) << report;
  EXPECT_NEAR(m.lever_arm_m[1], -0.39, 3.0 * m.lever_arm_sigma_m[1] + 0.01) << report;
  EXPECT_TRUE(estimated(s, "lever_arm_x_m") && estimated(s, "latency_s"));
  EXPECT_NE(report.find("estimated beside it: the antenna"), std::string::npos) << report;
  expect_a_usable_answer_that_covers_the_truth(s, drive);
}

// The same beside a heading.csv read 2.3 degrees off, no Doppler column, the drive at seed 33, the
// antenna 0.81 m behind the axle, the fixes 107 ms late: the heading is found first, the latency
// alone (128 ms) leaves the fixes 3.3 times their noise, and the lever arm beside it is fitted
// with the heading held estimated (-25.8 mm at a sigma of 7.5 mm, refused, before).
TEST(LatencyDetection, AnAntennaBesideALagIsFoundWithTheHeadingFoundBefore) {
  sim::Scenario scenario = urban_with_precise_fixes(0.02, 0.107);
  scenario.seeds.noise = scenario.seeds.trajectory = 33;
  scenario.gnss.lever_arm_x_m = -0.81;
  scenario.gnss.lever_arm_y_m = 0.05;
  scenario.heading.bias_rad = -0.041;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const auto [s, report] = calibrated_with_lag_and_mounting(drive);
  ASSERT_TRUE(s.latency_detection && s.mounting_detection);
  const BatchSummary::MountingDetection& m = *s.mounting_detection;
  EXPECT_TRUE(m.found_beside_latency && m.heading_bias) << report;
  EXPECT_NEAR(m.lever_arm_m[0], -0.81, 3.0 * m.lever_arm_sigma_m[0] + 0.01) << report;
  // The heading as the fit returned estimates it, not as the fit before found it.
  for (const EstimatedParameter& p : s.parameters) {
    if (p.name == "heading_bias_rad") {
      EXPECT_DOUBLE_EQ(m.heading_bias_rad, p.value);
    }
  }
  EXPECT_NEAR(m.heading_bias_rad, -0.041, 3.0 * m.heading_bias_sigma_rad + 0.002) << report;
  expect_a_usable_answer_that_covers_the_truth(s, drive);
}

// A lag that the Doppler speed's dependence shows and its fit takes (50 ms for 65), beside an
// antenna 1.98 m ahead that leaves the fixes 1.9 times their noise: the lever arm is fitted beside
// the latency, which then comes out right. Its x within 3 cm: the Doppler speed takes the rear
// axle's side slip in the turns (until 2026-12-06 it did not, x came out 3-8 cm short and the
// Doppler residual followed v^2 beyond the model's verdict: docs/batch-calibration.md, "Precise
// fixes' mountings").
TEST(LatencyDetection, AnAntennaAheadBesideALagTheDopplerSpeedShowsIsFoundWithIt) {
  sim::Scenario scenario = urban_with_gnss_latency(0.065, 30);
  scenario.gnss.sigma_m = 0.02;
  scenario.gnss.lever_arm_x_m = 1.98;
  scenario.gnss.lever_arm_y_m = -0.07;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const auto [s, report] = calibrated_with_lag_and_mounting(drive);
  ASSERT_TRUE(s.latency_detection && s.mounting_detection);
  EXPECT_FALSE(s.latency_detection->by_gnss_noise) << report;
  EXPECT_NEAR(s.latency_detection->latency_s, 0.065, 3.0 * s.latency_detection->sigma_s + 0.002);
  const BatchSummary::MountingDetection& m = *s.mounting_detection;
  EXPECT_TRUE(m.found_beside_latency && m.taken) << report;
  EXPECT_NEAR(m.lever_arm_m[0], 1.98, 0.03) << report;
  EXPECT_NEAR(m.lever_arm_m[1], -0.07, 0.02) << report;
  // Both against the fit with neither.
  EXPECT_DOUBLE_EQ(m.circumference_without_m[0], s.latency_detection->circumference_without_m[0]);
  expect_a_usable_answer_that_covers_the_truth(s, drive);
}

// heading.csv read 0.071 rad off beside RTK fixes 149 ms late from an antenna 2.91 m ahead and
// 0.58 m left (the mounting bench's run 7): with the fixes far off the path the poses' heading
// follows heading.csv and its residual shows nothing; the fit of the latency and the lever arm
// holds them to the fixes again and shows it, and the heading is fitted beside them.
TEST(LatencyDetection, AHeadingTheFirstFitsWideFixesHidIsFoundBesideTheLagAndTheAntenna) {
  sim::Scenario scenario = urban_with_gnss_latency(0.149, 7, 0.071);
  scenario.gnss.sigma_m = 0.02;
  scenario.gnss.lever_arm_x_m = 2.91;
  scenario.gnss.lever_arm_y_m = 0.58;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const auto [s, report] = calibrated_with_lag_and_mounting(drive);
  ASSERT_TRUE(s.latency_detection && s.mounting_detection);
  const BatchSummary::MountingDetection& m = *s.mounting_detection;
  EXPECT_TRUE(m.found_beside_latency && m.taken && m.heading_bias) << report;
  ASSERT_TRUE(m.heading_after.has_value()) << report;
  // The fit before the lever arm did not show it; the one with it did.
  EXPECT_LT(std::abs(m.signature.heading_mean_rad),
            BatchOptions::kMountingSigmas * m.signature.heading_standard_error_rad);
  EXPECT_GT(std::abs(m.heading_after->seen_rad),
            BatchOptions::kMountingSigmas * m.heading_after->seen_standard_error_rad);
  EXPECT_NEAR(m.heading_bias_rad, 0.071, 3.0 * m.heading_bias_sigma_rad + 0.002) << report;
  EXPECT_TRUE(estimated(s, "heading_bias_rad") && estimated(s, "lever_arm_x_m") &&
              estimated(s, "latency_s"));
  // The others' values are those of the fit returned, beside the heading.
  for (const EstimatedParameter& p : s.parameters) {
    if (p.name == "lever_arm_y_m") {
      EXPECT_DOUBLE_EQ(m.lever_arm_m[1], p.value);
    }
    if (p.name == "latency_s") {
      EXPECT_DOUBLE_EQ(s.latency_detection->latency_s, p.value);
    }
  }
  EXPECT_DOUBLE_EQ(m.heading_after->circumference_with_m[0], s.estimate.circumference_rl_m);
  EXPECT_TRUE(m.heading_after->beside_latency);
  EXPECT_NE(report.find("; then the fit with the antenna and the latency (below) left heading.csv"),
            std::string::npos)
      << report;
  expect_a_usable_answer_that_covers_the_truth(s, drive);
}

// The same with a lag alone beside heading.csv read 1.1 degrees off (run 14): the heading
// detection is a mounting of its own, found against the latency's fit.
TEST(LatencyDetection, AHeadingBesideALagInPreciseFixesIsFoundAfterTheLatency) {
  sim::Scenario scenario = urban_with_precise_fixes(0.02, 0.148);
  scenario.seeds.noise = scenario.seeds.trajectory = 14;
  scenario.heading.bias_rad = -0.019;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const auto [s, report] = calibrated_with_lag_and_mounting(drive);
  ASSERT_TRUE(s.latency_detection && s.mounting_detection);
  const BatchSummary::MountingDetection& m = *s.mounting_detection;
  EXPECT_TRUE(m.taken && m.heading_bias && !m.lever_arm) << report;
  ASSERT_TRUE(m.heading_after.has_value()) << report;
  EXPECT_TRUE(m.heading_after->beside_latency);
  // Against the latency's fit: the circumferences the latency line reports moved to.
  EXPECT_DOUBLE_EQ(m.circumference_without_m[0], m.heading_after->circumference_without_m[0]);
  EXPECT_NE(m.circumference_without_m[0], s.latency_detection->circumference_without_m[0]);
  EXPECT_NEAR(m.heading_bias_rad, -0.019, 3.0 * m.heading_bias_sigma_rad + 0.002) << report;
  EXPECT_NE(report.find("mounting     the fit with the latency (below) left heading.csv"),
            std::string::npos)
      << report;
  expect_a_usable_answer_that_covers_the_truth(s, drive);
}

// Fixes whose stated noise is a fifth of theirs widen the same way, and no latency narrows them.
TEST(LatencyDetection, FixesNoisierThanStatedAreNoLag) {
  Log log = simulated_log(sim::simulate(urban_with_precise_fixes(0.1, 0.0)));
  for (double& sigma : log.gnss.sigma_m) sigma = 0.02;
  const BatchSummary s = calibrate_batch(log);
  const std::string report = s.full_report();
  ASSERT_TRUE(s.latency_detection.has_value()) << report;
  EXPECT_TRUE(s.latency_detection->by_gnss_noise);
  EXPECT_FALSE(s.latency_detection->taken) << report;
  EXPECT_FALSE(estimated(s, "latency_s"));
  EXPECT_NE(report.find("the noise is not a lag's, kept without the latency"), std::string::npos)
      << report;
  EXPECT_TRUE(s.gnss_noise.adapted);
}

// RTK-grade fixes (2 cm) stamped 150 ms late: a latency stated or estimated places each fix at the
// instant it reports (BatchProblem::visit_fixes), as the same drive's fixes stamped right. Taken
// to first order in the whole latency, the fixes' residuals were 3.7 cm RMS (the noise adapted to
// it, sigma 8.7 mm) and the latency estimated 144.4 ms at a sigma of 0.3 ms.
TEST(LatencyDetection, AStatedOrEstimatedLatencyPlacesRtkFixesAtTheInstantTheyReport) {
  const sim::Scenario lagged = urban_with_precise_fixes(0.02, 0.15);
  const sim::Scenario unlagged = urban_with_precise_fixes(0.02, 0.0);
  BatchOptions options;
  options.max_sigma_circumference_m = 0.05;
  const BatchSummary clean = calibrate_batch(simulated_log(sim::simulate(unlagged)), options);
  const Log log = simulated_log(sim::simulate(lagged));
  options.latency_s = 0.15;
  const BatchSummary stated = calibrate_batch(log, options);
  EXPECT_FALSE(stated.gnss_noise.adapted) << stated.full_report();
  EXPECT_NEAR(stated.gnss_noise.residual_sigma_m, clean.gnss_noise.residual_sigma_m, 0.002);
  EXPECT_NEAR(stated.estimate.circumference_rl_m, clean.estimate.circumference_rl_m, 3e-4)
      << stated.full_report() << clean.full_report();
  options.latency_s = 0.0;
  options.estimate_latency = true;
  const BatchSummary fitted = calibrate_batch(log, options);
  const EstimatedParameter* latency = nullptr;
  for (const EstimatedParameter& p : fitted.parameters)
    if (p.name == "latency_s") latency = &p;
  ASSERT_NE(latency, nullptr);
  EXPECT_NEAR(latency->value, 0.15, 3.0 * latency->sigma + 0.001) << fitted.full_report();
  EXPECT_NEAR(fitted.estimate.circumference_rl_m, clean.estimate.circumference_rl_m, 3e-4);
}

}  // namespace
}  // namespace odocal
