// Model adequacy on simulated logs, through the batch: the ideal vehicle is explained; a vehicle
// whose wheels turn on a wider track than vehicle.yaml states is not (its heading residual
// follows curvature), until the batch estimates the track.

#include <gtest/gtest.h>

#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

sim::SimulatedDrive ideal_lap(double effective_track_m) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  scenario.route.laps = 1;
  scenario.vehicle.effective_track_width_m = effective_track_m;
  return sim::simulate(scenario);
}

TEST(ModelAdequacyBatch, IdealVehicleIsExplainedAWrongTrackIsNot) {
  const Log ideal = simulated_log(ideal_lap(0.0));
  EXPECT_TRUE(calibrate_batch(ideal).model_adequacy.explains)
      << calibrate_batch(ideal).model_adequacy.verdict;
  const Log wide = simulated_log(ideal_lap(1.76));  // wheels 10 % further apart than stated
  const ModelAdequacy fixed_track = calibrate_batch(wide).model_adequacy;
  EXPECT_FALSE(fixed_track.explains);
  EXPECT_NE(fixed_track.verdict.find("heading residual follows curvature"), std::string::npos)
      << fixed_track.verdict;
  BatchOptions with_track;
  with_track.estimate_track_width = true;
  EXPECT_TRUE(calibrate_batch(wide, with_track).model_adequacy.explains);
}

}  // namespace
}  // namespace odocal
