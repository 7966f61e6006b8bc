// BatchOptions::detect_mounting's rules alone: what a fit's residuals must show for a second fit,
// and what that fit must find to stand (the drives: mounting_detection_test.cpp).

#include <gtest/gtest.h>

#include <string>

#include "estimation/mounting_detection.hpp"

namespace odocal {
namespace {

TEST(MountingDetection, ASignatureNeedsBothSizeAndSignificance) {
  const BatchOptions options;
  MountingResiduals r;
  r.gnss = r.heading = true;
  r.gnss_standard_error_m = {0.001, 0.001};
  r.gnss_mean_m = {0.0, 0.02};  // certain, but too small to matter
  r.heading_standard_error_rad = 0.001;
  r.heading_mean_rad = 0.002;
  EXPECT_FALSE(batch::mounting_signature(r, options).has_value());
  r.gnss_mean_m = {0.0, 0.2};
  r.gnss_standard_error_m = {0.05, 0.05};  // large, but 4 standard errors
  EXPECT_FALSE(batch::mounting_signature(r, options).has_value());
  r.gnss_standard_error_m = {0.03, 0.03};
  const auto lever = batch::mounting_signature(r, options);
  ASSERT_TRUE(lever.has_value());
  EXPECT_TRUE(lever->lever_arm);
  EXPECT_FALSE(lever->heading_bias);
  r.heading_mean_rad = -0.01;
  EXPECT_TRUE(batch::mounting_signature(r, options)->heading_bias);
  BatchOptions estimating = options;
  estimating.estimate_lever_arm = estimating.estimate_heading_bias = true;
  EXPECT_FALSE(batch::mounting_signature(r, estimating).has_value());
  r = {};
  r.doppler = true;
  r.doppler_left_m = 0.3;
  r.doppler_left_standard_error_m = 0.01;
  EXPECT_TRUE(batch::mounting_signature(r, options)->lever_arm);
}

TEST(MountingDetection, TheSecondFitStandsOnlyWhereWhatItFindsIsSignificant) {
  const BatchOptions options;
  BatchSummary without, with;
  without.estimate.circumference_rl_m = 1.96;
  without.solves = 4;
  with.estimate.circumference_rl_m = 1.965;
  with.termination = Termination::kConverged;
  with.solves = 5;
  with.parameters = {{"lever_arm_x_m", 0.02, 0.05, true, true, ""},
                     {"lever_arm_y_m", 0.04, 0.005, true, true, ""}};
  const batch::MountingSignature lever{.lever_arm = true, .heading_bias = false};
  // 8 sigma, but 4.5 cm: kept without.
  BatchSummary kept = batch::take_mounting_where_significant(without, with, lever, options);
  ASSERT_TRUE(kept.mounting_detection.has_value());
  EXPECT_FALSE(kept.mounting_detection->taken);
  EXPECT_EQ(kept.solves, 4);
  EXPECT_EQ(kept.tyre_selection.other_solves, 5);
  with.parameters[1].value = 0.3;
  kept = batch::take_mounting_where_significant(without, with, lever, options);
  EXPECT_TRUE(kept.mounting_detection->taken);
  EXPECT_EQ(kept.solves, 5);
  EXPECT_DOUBLE_EQ(kept.mounting_detection->lever_arm_m[1], 0.3);
  EXPECT_DOUBLE_EQ(kept.mounting_detection->circumference_without_m[0], 1.96);
  EXPECT_DOUBLE_EQ(kept.mounting_detection->circumference_with_m[0], 1.965);
  // Its line says what its own fit moved, whatever the summary ends as (a latency found after).
  kept.estimate.circumference_rl_m = 1.97;
  EXPECT_NE(batch::mounting_detection_report(*kept.mounting_detection).find("by +5 / "),
            std::string::npos)
      << batch::mounting_detection_report(*kept.mounting_detection);
  // Where the second fit did not stand, the first does.
  with.termination = Termination::kNoConvergence;
  kept = batch::take_mounting_where_significant(without, with, lever, options);
  EXPECT_FALSE(kept.mounting_detection->taken);
  EXPECT_FALSE(kept.mounting_detection->fitted);
  EXPECT_NE(batch::mounting_detection_report(*kept.mounting_detection).find("did not stand"),
            std::string::npos);
}

}  // namespace
}  // namespace odocal
