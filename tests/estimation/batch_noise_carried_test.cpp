// A batch fit solved from the start under a GNSS noise carried over from another fit (the track
// prior's refit, the judge's): where its residuals show another noise, it adapts again against the
// configured sigma, not the carried one (docs/batch-calibration.md, "The track under its prior").

#include <gtest/gtest.h>

#include <optional>

#include "estimation/batch_fit.hpp"
#include "estimation/calibration_run.hpp"
#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

TEST(BatchNoiseCarried, AFitStartedUnderAWrongNoiseAdaptsAgainstTheConfiguredSigma) {
  // One ideal lap under 0.5 m of white GNSS noise, while 0.1 m is configured.
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  scenario.gnss.sigma_m = 0.5;
  Log log = simulated_log(sim::simulate(scenario));
  log.gnss.sigma_m.clear();
  CalibrationOptions claimed;
  claimed.reference.gnss_sigma_m = 0.1;
  claimed.judge_model_adequacy = false;
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kNone;

  BatchSummary unfitted;
  CalibrationRun run(log, claimed, CalibrationMethod::kBatch, unfitted);
  run.smooth_batch_heading(options.heading_tick_smoothing_s);
  BatchSummary fresh = unfitted;
  ASSERT_TRUE(batch::fit_model(run, options, claimed, std::nullopt, fresh));
  ASSERT_TRUE(fresh.gnss_noise.adapted);
  // Carried: three times the white noise the fresh fit found, and no correlated error (one
  // carried is that fit's answer already, and is not adapted again).
  const std::optional<batch::GnssNoiseModel> found = batch::adapted_noise(fresh.gnss_noise);
  ASSERT_TRUE(found);
  const batch::GnssNoiseModel wrong{.white_scale = 3.0 * found->white_scale};
  BatchSummary carried = unfitted;
  ASSERT_TRUE(batch::fit_model(run, options, claimed, std::nullopt, carried, {.noise = wrong}));

  ASSERT_TRUE(carried.gnss_noise.adapted);
  EXPECT_NEAR(carried.gnss_noise.configured_sigma_m, 0.1, 1e-9);
  const std::optional<batch::GnssNoiseModel> again = batch::adapted_noise(carried.gnss_noise);
  ASSERT_TRUE(again);
  EXPECT_NEAR(again->white_scale, found->white_scale, 0.25 * found->white_scale);
  // Solved under the noise the residuals show, as the fresh fit was: the same sigma.
  EXPECT_NEAR(carried.sigma_rl_m(), fresh.sigma_rl_m(), 0.25 * fresh.sigma_rl_m());
  EXPECT_NEAR(carried.sigma_rr_m(), fresh.sigma_rr_m(), 0.25 * fresh.sigma_rr_m());
}

}  // namespace
}  // namespace odocal
