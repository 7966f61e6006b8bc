// The calibration JSON's model-adequacy entry: a model that was not judged is neither explained
// nor not (explains: null), so that a reader filtering on it is not told "explained". Its
// coverage carries the drive's distance-weighted mean v^2, which a tyre's growth goes with.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "odocal/estimation/calibration.hpp"
#include "odocal/io/calibration_io.hpp"

namespace odocal {
namespace {

nlohmann::json adequacy_json(const ModelAdequacy& adequacy) {
  IterativeSummary summary;
  summary.model_adequacy = adequacy;
  return summary_to_json(AnyCalibrationSummary(summary), CalibrationConfig{});
}

TEST(CalibrationJson, AnUnjudgedModelIsNeitherExplainedNorNot) {
  ModelAdequacy unjudged;
  unjudged.verdict = "too few moving keyframe intervals to judge the model";
  const nlohmann::json json = adequacy_json(unjudged).at("model_adequacy");
  EXPECT_FALSE(json.at("judged").get<bool>());
  EXPECT_TRUE(json.at("explains").is_null());
  EXPECT_EQ(json.at("verdict"), unjudged.verdict);

  ModelAdequacy explained = unjudged;
  explained.judged = explained.explains = true;
  explained.verdict = "the two-wheel model explains this log";
  EXPECT_TRUE(adequacy_json(explained).at("model_adequacy").at("explains").get<bool>());
  // Not asked for (judge_model_adequacy off): no entry at all.
  EXPECT_FALSE(adequacy_json(ModelAdequacy{}).contains("model_adequacy"));
}

TEST(CalibrationJson, CoverageCarriesTheDistanceWeightedMeanSquareSpeed) {
  IterativeSummary summary;
  summary.coverage.distance_m = 2000.0;
  summary.coverage.distance_speed_squared_m3ps2 = 1000.0 * 100.0 + 1000.0 * 400.0;
  const nlohmann::json json = summary_to_json(AnyCalibrationSummary(summary), CalibrationConfig{});
  EXPECT_DOUBLE_EQ(json.at("coverage").at("mean_square_speed_m2ps2").get<double>(), 250.0);
}

}  // namespace
}  // namespace odocal
