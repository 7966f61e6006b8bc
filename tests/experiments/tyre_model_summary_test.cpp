// The tyre model summary and its targets against hand-computed figures.

#include <gtest/gtest.h>

#include <cmath>

#include "experiments/tyre_model_experiment.hpp"

namespace odocal::experiments {
namespace {

nlohmann::json run(double error_mm, double sigma_mm, double dr_m, bool with_model,
                   double seconds = 1.0, double walk_deg = 0.0) {
  return {{"error_rl_mm", error_mm},           {"error_rr_mm", -error_mm},
          {"reported_sigma_rl_mm", sigma_mm},  {"reported_sigma_rr_mm", sigma_mm},
          {"dr_mean_position_m", dr_m},        {"dr_mean_heading_deg", 0.1},
          {"milliseconds", 1e3 * seconds},     {"tyre_model_used", with_model},
          {"accelerometer_walk_deg", walk_deg}};
}

// Both drivetrains alike: none 10 mm off, extended 0.5 mm inside its sigma, physical 3 mm
// outside its, auto as extended; ideal: none and auto 0.2 mm off with 4 m of dead reckoning.
// The grip-sharing driver: rear 0.8 mm inside its sigma with 9 m, front 1.5 mm outside its with
// 30 m, its ideal mode 3 m; with a quieter accelerometer rear 0.6 mm with 6 m (walk 0.4 and 0.6
// deg), front 0.4 mm with 4.5 m. With a drive force column: rear 0.9 mm with 8 m, front 0.3 mm
// with 6 m.
nlohmann::json seed(int n, double extended_dr_m) {
  nlohmann::json drive{{"none", run(10.0, 1.0, 500.0, false)},
                       {"extended", run(0.5, 1.0, extended_dr_m, true, 2.0 + n)},
                       {"physical", run(3.0, 0.5, 50.0, true, 1.5)},
                       {"auto", run(0.5, 1.0, extended_dr_m, true)}};
  return {{"seed", n},
          {"realistic", {{"rear", drive}, {"front", drive}}},
          {"realistic_drive_force",
           {{"rear", {{"auto", run(0.9, 1.0, 8.0, true)}}},
            {"front", {{"auto", run(0.3, 1.0, 6.0, true)}}}}},
          {"ideal", {{"none", run(0.2, 0.1, 4.0, false)}, {"auto", run(0.2, 0.1, 4.0, false)}}},
          {"grip_sharing",
           {{"rear", {{"auto", run(0.8, 1.0, 9.0, true)}}},
            {"front", {{"auto", run(1.5, 0.4, 30.0, true)}}}}},
          {"grip_sharing_quiet_accelerometer",
           {{"rear", {{"auto", run(0.6, 1.0, 6.0, true, 1.0, n == 1 ? 0.4 : 0.6)}}},
            {"front", {{"auto", run(0.4, 1.0, 4.5, true, 1.0, 0.3)}}}}},
          {"grip_sharing_ideal", {{"none", run(0.1, 0.1, 3.0, false)}}}};
}

nlohmann::json urban(int n, double calibrated) {
  return {{"seed", n},
          {"nominal_median_drift_percent", 0.7},
          {"calibrated_median_drift_percent", calibrated},
          {"true_static_median_drift_percent", 0.6},
          {"exact_wheels_median_drift_percent", 0.25 + 0.01 * n},
          {"reference_only_median_drift_percent", 0.22},
          {"ideal_true_median_drift_percent", 0.2},
          {"calibrated_raw_ticks_median_drift_percent", calibrated + 0.1},
          {"ideal_true_raw_ticks_median_drift_percent", 0.3}};
}

const nlohmann::json* find_target(const nlohmann::json& summary, const std::string& start) {
  for (const nlohmann::json& t : summary.at("targets"))
    if (t.at("target").get<std::string>().starts_with(start)) return &t;
  return nullptr;
}

TEST(TyreModelSummary, TargetsFollowTheRows) {
  // Dead reckoning 10 and 14 m with extended/auto (mean 12 m, 3x the ideal 4 m: on the limit).
  const nlohmann::json summary = summarise_tyre_models(
      {seed(1, 10.0), seed(2, 14.0)}, {urban(1, 0.2), urban(2, 0.5), urban(3, 0.25)});
  ASSERT_EQ(summary.at("rows").size(), 17u);
  const nlohmann::json& rear_none = summary["rows"][0];
  EXPECT_EQ(rear_none["tyre_model"], "none");
  EXPECT_DOUBLE_EQ(rear_none["mean_abs_error_mm"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(rear_none["within_3_reported_sigma"].get<double>(), 0.0);
  const nlohmann::json& rear_extended = summary["rows"][1];
  EXPECT_DOUBLE_EQ(rear_extended["within_3_reported_sigma"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(rear_extended["mean_dr_position_m"].get<double>(), 12.0);
  EXPECT_DOUBLE_EQ(rear_extended["max_seconds"].get<double>(), 4.0);
  EXPECT_EQ(rear_extended["runs_with_tyre_model"], 2);
  const nlohmann::json& rear_physical = summary["rows"][2];
  EXPECT_EQ(rear_physical["tyre_model"], "physical");
  EXPECT_DOUBLE_EQ(rear_physical["within_3_reported_sigma"].get<double>(), 0.0);

  const nlohmann::json* error = find_target(summary, "rear-wheel drive, auto: mean abs error");
  ASSERT_NE(error, nullptr);
  EXPECT_TRUE((*error)["met"].get<bool>());
  const nlohmann::json* dr = find_target(summary, "front-wheel drive, auto: whole-log DR");
  ASSERT_NE(dr, nullptr);
  EXPECT_DOUBLE_EQ((*dr)["measured"].get<double>(), 3.0);
  EXPECT_TRUE((*dr)["met"].get<bool>());
  const nlohmann::json* time = find_target(summary, "rear-wheel drive, extended: slowest");
  ASSERT_NE(time, nullptr);
  EXPECT_FALSE((*time)["met"].get<bool>());  // 4 s against 3 s
  const nlohmann::json* physical_time = find_target(summary, "rear-wheel drive, physical: slowest");
  ASSERT_NE(physical_time, nullptr);
  EXPECT_TRUE((*physical_time)["met"].get<bool>());
  const nlohmann::json* ideal = find_target(summary, "ideal, auto: change");
  ASSERT_NE(ideal, nullptr);
  EXPECT_TRUE((*ideal)["met"].get<bool>());
  // The circuit driver's drives with a drive force column: beside the targets, against the ideal
  // mode's 4 m.
  const nlohmann::json& forced_rear = summary["rows"][8];
  EXPECT_EQ(forced_rear["mode"], "realistic, drive force column (100 N)");
  EXPECT_EQ(forced_rear["drivetrain"], "rear");
  EXPECT_DOUBLE_EQ(forced_rear["mean_abs_error_mm"].get<double>(), 0.9);
  EXPECT_DOUBLE_EQ(forced_rear["dr_over_ideal"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(summary["rows"][9]["dr_over_ideal"].get<double>(), 1.5);
  EXPECT_EQ(find_target(summary, "realistic, drive force"), nullptr);
  // The grip-sharing driver's rows and targets, its dead reckoning against its own ideal mode.
  EXPECT_EQ(summary["rows"][12]["mode"], "realistic, grip-sharing driver");
  EXPECT_EQ(summary["rows"][16]["mode"], "ideal, grip-sharing driver");
  // The same driver with a quieter accelerometer: its rows beside the targets, not among them.
  const nlohmann::json& quiet_rear = summary["rows"][14];
  EXPECT_EQ(quiet_rear["mode"], "realistic, grip-sharing driver, 0.05 m/s² accelerometer");
  EXPECT_EQ(quiet_rear["drivetrain"], "rear");
  EXPECT_DOUBLE_EQ(quiet_rear["dr_over_ideal"].get<double>(), 2.0);  // 6 m over 3 m
  EXPECT_DOUBLE_EQ(quiet_rear["mean_accelerometer_walk_deg"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(summary["rows"][15]["mean_abs_error_mm"].get<double>(), 0.4);
  for (const nlohmann::json& t : summary.at("targets"))
    EXPECT_EQ(t.at("target").get<std::string>().find("accelerometer"), std::string::npos);
  const auto met = [&](const std::string& what) {
    const nlohmann::json* t = find_target(summary, "grip-sharing driver, " + what);
    EXPECT_NE(t, nullptr) << what;
    return t != nullptr && (*t)["met"].get<bool>();
  };
  EXPECT_TRUE(met("rear-wheel drive, auto: mean abs error"));
  EXPECT_TRUE(met("rear-wheel drive, auto: share inside 3"));
  EXPECT_TRUE(met("rear-wheel drive, auto: whole-log DR"));  // 9 m against 3 x 3 m: the limit
  EXPECT_FALSE(met("front-wheel drive, auto: mean abs error"));
  EXPECT_FALSE(met("front-wheel drive, auto: share inside 3"));  // 1.5 mm against 3 x 0.4 mm
  EXPECT_FALSE(met("front-wheel drive, auto: whole-log DR"));
  const nlohmann::json* drift = find_target(summary, "urban");
  ASSERT_NE(drift, nullptr);
  EXPECT_DOUBLE_EQ((*drift)["measured"].get<double>(), 0.25);  // the median of three seeds
  EXPECT_TRUE((*drift)["met"].get<bool>());
  // The unsmoothed tick counts' figures are reported beside it, not judged.
  EXPECT_DOUBLE_EQ(summary["urban"]["calibrated_raw_ticks_median_drift_percent"].get<double>(),
                   0.35);
  EXPECT_DOUBLE_EQ(summary["urban"]["ideal_true_raw_ticks_median_drift_percent"].get<double>(),
                   0.3);
  // So are the drive's floors: its wheels made exact, and its reference's uncertainty alone.
  EXPECT_DOUBLE_EQ(summary["urban"]["exact_wheels_median_drift_percent"].get<double>(), 0.27);
  EXPECT_DOUBLE_EQ(summary["urban"]["reference_only_median_drift_percent"].get<double>(), 0.22);
  // Calibrated minus exact wheels per seed: -0.06, +0.23, -0.03; mean 0.0467, sample sigma 0.1595.
  EXPECT_NEAR(summary["urban"]["calibrated_minus_exact_wheels_mean_percent"].get<double>(),
              0.14 / 3.0, 1e-12);
  EXPECT_NEAR(
      summary["urban"]["calibrated_minus_exact_wheels_standard_error_percent"].get<double>(),
      std::sqrt((std::pow(-0.06 - 0.14 / 3, 2) + std::pow(0.23 - 0.14 / 3, 2) +
                 std::pow(-0.03 - 0.14 / 3, 2)) /
                2.0) /
          std::sqrt(3.0),
      1e-12);
  EXPECT_THROW(summarise_tyre_models({}, {}), std::exception);
}

TEST(TyreModelSummary, AnInfiniteSigmaWrittenAsNullCoversItsError) {
  // A rank-deficient fit reports an infinite sigma, which JSON writes as null.
  nlohmann::json first = seed(1, 10.0), second = seed(2, 10.0);
  for (const char* key : {"reported_sigma_rl_mm", "reported_sigma_rr_mm"})
    first["realistic"]["rear"]["none"][key] = nullptr;
  const nlohmann::json summary = summarise_tyre_models({first, second}, {urban(1, 0.2)});
  const nlohmann::json& rear_none = summary["rows"][0];
  ASSERT_EQ(rear_none["tyre_model"], "none");
  EXPECT_DOUBLE_EQ(rear_none["within_3_reported_sigma"].get<double>(), 0.5);
}

TEST(TyreModelSummary, TheIdealRunsAreComparedSeedBySeed) {
  // auto 0.3 and 0.2 mm off where none is 0.2 mm off on both: differences +0.1 and 0.
  nlohmann::json first = seed(1, 10.0), second = seed(2, 10.0);
  first["ideal"]["auto"] = run(0.3, 0.05, 4.0, false);
  second["ideal"]["auto"] = run(0.2, 0.05, 4.0, false);
  const nlohmann::json summary = summarise_tyre_models({first, second}, {urban(1, 0.2)});
  const nlohmann::json& ideal = summary.at("ideal_auto_against_none");
  EXPECT_NEAR(ideal.at("mean_abs_error_difference_mm").get<double>(), 0.05, 1e-12);
  // Sample sigma of (0.1, 0) is 0.1 / sqrt(2); over sqrt(2) seeds, 0.05.
  EXPECT_NEAR(ideal.at("difference_standard_error_mm").get<double>(), 0.05, 1e-12);
  EXPECT_DOUBLE_EQ(ideal.at("none_mean_reported_sigma_mm").get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(ideal.at("auto_mean_reported_sigma_mm").get<double>(), 0.05);
  // A run without a sigma (written as null) leaves the mean without one, as in the coverage.
  first["ideal"]["auto"]["reported_sigma_rl_mm"] = nullptr;
  const nlohmann::json unsure = summarise_tyre_models({first, second}, {urban(1, 0.2)});
  EXPECT_TRUE(std::isinf(
      unsure.at("ideal_auto_against_none").at("auto_mean_reported_sigma_mm").get<double>()));
  EXPECT_NEAR(unsure.at("ideal_auto_against_none").at("mean_abs_error_difference_mm").get<double>(),
              0.05, 1e-12);
}

}  // namespace
}  // namespace odocal::experiments
