// The batch's split-sample check (BatchOptions::consistency_parts) on simulated drives with a
// known truth: a receiver whose error wanders over a minute, which the residuals hide, and a white
// one. Labelled slow.

#include "estimation/batch_consistency.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>

#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/estimation/log_window.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

// A built-in drive (urban: 2 km in 300 s; circuit: 3 laps, 13.7 km in 600 s), kinematic, its
// receiver's white 3 m at 50 Hz on a Gauss-Markov error of `wander_m` over 60 s (none: white only).
sim::SimulatedDrive ideal_drive(const char* name, double wander_m, std::uint64_t seed) {
  sim::Scenario scenario = load_scenario(name);
  scenario.ideal = true;
  scenario.gnss.gauss_markov_sigma_m = wander_m;
  scenario.gnss.gauss_markov_tau_s = 60.0;
  scenario.seeds = {seed, seed};
  return sim::simulate(scenario);
}
sim::SimulatedDrive urban_drive(double wander_m, std::uint64_t seed) {
  return ideal_drive("urban", wander_m, seed);
}

double error_in_sigmas(const BatchSummary& result, const sim::SimulatedDrive& drive) {
  return std::abs(result.estimate.circumference_rl_m - drive.true_params.circumference_rl_m) /
         result.sigma_rl_m();
}

BatchOptions plain(int parts) {
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kNone;
  options.consistency_parts = parts;
  return options;
}

// A white receiver's urban drive (seed 1) calibrated without the check and with it in `parts`.
struct WithAndWithout {
  Log log;
  BatchSummary unchecked, checked;
};
WithAndWithout white_urban_drive_checked(int parts) {
  WithAndWithout out{simulated_log(urban_drive(0.0, 1)), {}, {}};
  out.unchecked = calibrate_batch(out.log, plain(0));
  out.checked = calibrate_batch(out.log, plain(parts));
  return out;
}

TEST(BatchConsistency, TheBoundIsTheChiSquareQuantile) {
  // Independent truth: the chi-square distribution's 95 % quantiles, tabulated.
  const std::pair<int, double> quantiles[] = {{1, 3.841459},  {2, 5.991465},   {3, 7.814728},
                                              {5, 11.070498}, {10, 18.307038}, {19, 30.143527}};
  for (const auto& [dof, q] : quantiles) {
    const double exact = std::sqrt(q / dof);
    EXPECT_NEAR(batch::birge_ratio_bound(dof), exact, (dof == 1 ? 0.013 : 0.005) * exact) << dof;
  }
}

TEST(BatchConsistency, AWanderingReceiverThatTheResidualsHideWidensTheSigma) {
  const sim::SimulatedDrive drive = urban_drive(1.0, 2);
  const Log log = simulated_log(drive);
  BatchOptions options = plain(0);
  options.max_sigma_circumference_m = 0.01;  // the sigma is what is compared, not the refusal
  const BatchSummary unchecked = calibrate_batch(log, options);
  options.consistency_parts = 4;
  const BatchSummary checked = calibrate_batch(log, options);
  SCOPED_TRACE(checked.full_report());
  // The case: the residuals show nothing, and the error is far outside the sigma.
  EXPECT_FALSE(unchecked.gnss_noise.adapted);
  ASSERT_GT(error_in_sigmas(unchecked, drive), 4.0);
  ASSERT_TRUE(checked.consistency);
  const PartsConsistency& c = *checked.consistency;
  EXPECT_EQ(c.fitted_parts, 4u);
  EXPECT_FALSE(c.consistent);
  EXPECT_GT(c.birge_ratio[0], c.bound);
  EXPECT_NEAR(c.sigma_scale[0], c.birge_ratio[0], 1e-12);
  // The estimate stands, its sigma widened by R, and it covers the error.
  EXPECT_EQ(checked.estimate.circumference_rl_m, unchecked.estimate.circumference_rl_m);
  EXPECT_NEAR(checked.sigma_rl_m(), c.birge_ratio[0] * unchecked.sigma_rl_m(), 1e-12);
  EXPECT_NEAR(checked.parameters[0].sigma, checked.sigma_rl_m(), 1e-12);
  EXPECT_LT(error_in_sigmas(checked, drive), 3.0);
  EXPECT_TRUE(checked.usable());
  EXPECT_NE(checked.note.find("disagree with the whole log beyond their sigma"), std::string::npos);
  EXPECT_NE(checked.full_report().find("consistency  4 of the log's 4 parts"), std::string::npos);
  // At the default threshold of 1 mm the widened sigma refuses the result and says why.
  options.max_sigma_circumference_m = 1e-3;
  const BatchSummary refused = calibrate_batch(log, options);
  EXPECT_EQ(refused.termination, Termination::kNotIdentifiable);
  EXPECT_FALSE(refused.parameters[0].identified);
  EXPECT_NE(refused.message.find("parts"), std::string::npos);
  EXPECT_NE(refused.identifiability.find("circumference_rl_m"), std::string::npos);
}

TEST(BatchConsistency, APartThatDeadReckonsWorseThanNominalStillCounts) {
  // The circuit under a wandering receiver (seed 2): some of its 150 s parts, calibrated alone
  // with the defaults, dead-reckon their stretch worse than nominal and are refused as
  // implausible; in the check each is a sound estimate with its sigma, and counts.
  const sim::SimulatedDrive drive = ideal_drive("circuit", 1.0, 2);
  const Log log = simulated_log(drive);
  BatchOptions options = plain(4);
  options.max_sigma_circumference_m = 0.01;
  const BatchSummary checked = calibrate_batch(log, options);
  SCOPED_TRACE(checked.full_report());
  const PartsConsistency& c = checked.consistency.value();  // throws where it is missing
  int refused_alone = 0;
  for (const PartsConsistency::Part& part : c.parts) {
    const BatchSummary alone = calibrate_batch(crop_log(log, part.from_s, part.to_s), plain(0));
    refused_alone += alone.termination == Termination::kImplausible;
  }
  EXPECT_GE(refused_alone, 1);
  EXPECT_EQ(c.fitted_parts, 4u);
  EXPECT_FALSE(c.consistent);
  EXPECT_LT(error_in_sigmas(checked, drive), 3.0);
}

TEST(BatchConsistency, AWhiteReceiverLeavesTheResultAsItIs) {
  const auto [log, unchecked, checked] = white_urban_drive_checked(4);
  SCOPED_TRACE(checked.full_report());
  const PartsConsistency& c = checked.consistency.value();  // throws where it is missing
  EXPECT_EQ(c.parts.size(), 4u);
  EXPECT_EQ(c.fitted_parts, 4u);
  EXPECT_TRUE(c.consistent);
  EXPECT_LT(c.birge_ratio[0], c.bound);
  EXPECT_LT(c.birge_ratio[1], c.bound);
  EXPECT_EQ(c.sigma_scale[0], 1.0);
  EXPECT_EQ(checked.sigma_rl_m(), unchecked.sigma_rl_m());
  EXPECT_EQ(checked.termination, unchecked.termination);
  EXPECT_TRUE(checked.usable());
  // The parts tile the log, and each part's sigma is wider than the whole log's.
  EXPECT_EQ(c.parts.front().from_s, log.wheels.t_s.front());
  EXPECT_EQ(c.parts.back().to_s, log.wheels.t_s.back());
  for (std::size_t k = 0; k + 1 < c.parts.size(); ++k)
    EXPECT_EQ(c.parts[k].to_s, c.parts[k + 1].from_s);
  for (const PartsConsistency::Part& part : c.parts)
    EXPECT_GT(part.sigma_m[0], checked.sigma_rl_m());
  const sim::SimulatedDrive drive = urban_drive(0.0, 1);
  EXPECT_LT(std::abs(checked.estimate.circumference_rl_m - drive.true_params.circumference_rl_m),
            3.0 * checked.sigma_rl_m());
  // Off (the default), nothing is checked.
  EXPECT_FALSE(unchecked.consistency);
}

TEST(BatchConsistency, PartsTooShortToCalibrateAreLeftOutAndSaid) {
  // 20 parts of 15 s: some hold a stop and too little motion to calibrate alone.
  const auto [log, unchecked, checked] = white_urban_drive_checked(20);
  SCOPED_TRACE(checked.full_report());
  const PartsConsistency& c = checked.consistency.value();  // throws where it is missing
  EXPECT_EQ(c.parts.size(), 20u);
  EXPECT_LT(c.fitted_parts, 20u);
  EXPECT_GE(c.fitted_parts, 2u);
  EXPECT_NE(c.verdict.find(std::to_string(c.fitted_parts) + " of the log's 20 parts"),
            std::string::npos);
  for (const PartsConsistency::Part& part : c.parts) {
    if (!part.fitted) continue;
    EXPECT_TRUE(std::isfinite(part.sigma_m[0]) && part.sigma_m[0] > 0.0);
  }
  EXPECT_NEAR(c.bound, batch::birge_ratio_bound(static_cast<int>(c.fitted_parts) - 1), 1e-15);
  EXPECT_TRUE(std::isfinite(checked.sigma_rl_m()));
  EXPECT_GE(checked.sigma_rl_m(), unchecked.sigma_rl_m());
}

}  // namespace
}  // namespace odocal
