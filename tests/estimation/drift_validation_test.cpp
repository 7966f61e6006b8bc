// Held-out drift on a closed-form drive: a straight line whose reference is exact, so a 1 %
// circumference error drifts exactly 1 % in every window and the true parameters do not drift.

#include "odocal/estimation/drift_validation.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "odocal/error.hpp"

namespace odocal {
namespace {

struct StraightDrive {
  WheelStream wheels;
  ReferenceTrajectory reference;
};

// 10 m/s east for `duration_s` at 10 Hz with 2 m wheels.
StraightDrive straight_drive(double duration_s) {
  StraightDrive d;
  for (int k = 0; k <= static_cast<int>(duration_s * 10); ++k) {
    d.wheels.t_s.push_back(0.1 * k);
    d.wheels.rev_rl.push_back(k == 0 ? 0.0 : 0.5);
    d.wheels.rev_rr.push_back(k == 0 ? 0.0 : 0.5);
    d.reference.poses.emplace_back(1.0 * k, 0.0, 0.0);
  }
  return d;
}

TEST(DriftValidation, OnePercentScaleErrorDriftsOnePercentPerWindow) {
  const StraightDrive d = straight_drive(130.0);
  const OdometryParams truth{2.0, 2.0, 1.6};
  const OdometryParams scaled{2.02, 2.02, 1.6};
  const DriftValidation v = validate_drift(d.wheels, d.reference, scaled, truth, {60.0, 20.0});
  ASSERT_EQ(v.nominal.size(), 2u);  // two full minutes; the 10 s tail is left out
  for (const WindowDrift& w : v.nominal) {
    EXPECT_NEAR(w.distance_m, 606.0, 1e-6);
    EXPECT_NEAR(w.end_error_m, 6.0, 1e-6);
    EXPECT_NEAR(w.drift_percent, 100.0 * 6.0 / 606.0, 1e-9);
  }
  EXPECT_NEAR(v.calibrated_statistics.p95_end_error_m, 0.0, 1e-9);
  EXPECT_NEAR(v.nominal_statistics.median_end_error_m, 6.0, 1e-6);
  EXPECT_EQ(v.calibrated_statistics.windows, 2u);
}

// Overlapping windows: one every 10 s over 130 s of 60 s windows starts at 0, 10, ..., 70 s.
TEST(DriftValidation, OverlappingWindowsStartEveryStep) {
  const StraightDrive d = straight_drive(130.0);
  const DriftValidation v =
      validate_drift(d.wheels, d.reference, {2.02, 2.02, 1.6}, {2.0, 2.0, 1.6}, {60.0, 20.0, 10.0});
  ASSERT_EQ(v.nominal.size(), 8u);
  for (std::size_t i = 0; i < v.nominal.size(); ++i) {
    EXPECT_NEAR(v.nominal[i].start_s, 10.0 * static_cast<double>(i), 1e-9);
    EXPECT_NEAR(v.nominal[i].end_error_m, 6.0, 1e-6);
  }
  EXPECT_THROW(validate_drift(d.wheels, d.reference, {2, 2, 1.6}, {2, 2, 1.6}, {60.0, 20.0, -1.0}),
               Error);
}

// With no minimum distance, a window spent standing still is still left out: its drift in % of
// no distance would be 0 / 0.
TEST(DriftValidation, AStandingWindowIsLeftOutEvenWithoutAMinimumDistance) {
  StraightDrive d = straight_drive(130.0);
  for (std::size_t k = 0; k <= 610; ++k) {  // standing for the first 61 s, then on east
    d.wheels.rev_rl[k] = d.wheels.rev_rr[k] = 0.0;
    d.reference.poses[k] = Pose2(0.0, 0.0, 0.0);
  }
  for (std::size_t k = 611; k < d.reference.poses.size(); ++k)
    d.reference.poses[k].x() = static_cast<double>(k) - 610.0;
  d.reference.covariance.assign(d.reference.poses.size(), Eigen::Matrix3d::Identity() * 1e-4);
  const OdometryParams truth{2.0, 2.0, 1.6};
  const DriftValidation v = validate_drift(d.wheels, d.reference, truth, truth, {60.0, 0.0});
  ASSERT_EQ(v.nominal.size(), 1u);  // the moving minute only
  EXPECT_NEAR(v.nominal[0].start_s, 60.0, 1e-9);
  EXPECT_TRUE(std::isfinite(v.nominal_statistics.median_drift_percent));
  EXPECT_TRUE(std::isfinite(v.reference->median_drift_percent));
}

TEST(DriftValidation, RefusesALogWithoutALongEnoughWindow) {
  const StraightDrive d = straight_drive(30.0);
  EXPECT_THROW(validate_drift(d.wheels, d.reference, {2, 2, 1.6}, {2, 2, 1.6}, {60.0, 20.0}),
               InsufficientDataError);
  EXPECT_THROW(validate_drift(d.wheels, d.reference, {2, 2, 1.6}, {2, 2, 1.6}, {-1.0, 20.0}),
               Error);
}

TEST(DriftValidation, RefusesAReferenceOfOtherWheels) {
  // The reference's times are its wheels': a stream shorter than it cannot be the one.
  StraightDrive d = straight_drive(130.0);
  d.reference.first_wheel_index = 5;
  try {
    validate_drift(d.wheels, d.reference, {2, 2, 1.6}, {2, 2, 1.6}, {60.0, 20.0});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("reaches past the wheel stream"), std::string::npos)
        << e.what();
  }
}

// The reference's own uncertainty: a heading error at a window's start turns its whole 600 m
// displacement (a half-normal across the track, sigma 600 m * sigma_yaw); position errors at start
// and end add as independent circular ones.
TEST(DriftValidation, TheReferencesUncertaintySaysWhatItAloneWouldShow) {
  StraightDrive d = straight_drive(130.0);
  const OdometryParams truth{2.0, 2.0, 1.6};
  const DriftValidation without = validate_drift(d.wheels, d.reference, truth, truth, {60.0, 20.0});
  EXPECT_FALSE(without.reference.has_value());  // no covariance, no claim

  d.reference.covariance.assign(d.reference.poses.size(),
                                Eigen::Vector3d(0.0, 0.0, 1e-6).asDiagonal());
  const DriftValidation heading = validate_drift(d.wheels, d.reference, truth, truth, {60.0, 20.0});
  ASSERT_TRUE(heading.reference.has_value());
  ASSERT_EQ(heading.reference->rms_m.size(), 2u);
  EXPECT_NEAR(heading.reference->rms_m[0], 0.6, 1e-9);
  EXPECT_NEAR(heading.reference->median_end_error_m, 0.6 * 0.6744898, 2e-3);
  EXPECT_NEAR(heading.reference->median_drift_percent, 100.0 * 0.6 * 0.6744898 / 600.0, 3e-4);

  d.reference.covariance.assign(d.reference.poses.size(),
                                Eigen::Vector3d(0.25, 0.25, 0.0).asDiagonal());
  const DriftValidation position =
      validate_drift(d.wheels, d.reference, truth, truth, {60.0, 20.0});
  EXPECT_NEAR(position.reference->median_end_error_m, std::sqrt(std::log(2.0)), 1e-6);

  d.reference.covariance.pop_back();
  EXPECT_THROW(validate_drift(d.wheels, d.reference, truth, truth, {60.0, 20.0}), Error);
}

// The reference measures the axle through the antenna: the one vehicle.yaml states stands, the
// one the calibration found fills in where it states none, and nothing found changes nothing.
TEST(DriftValidation, TakesTheFoundAntennaOnlyWhereVehicleYamlStatesNone) {
  VehicleConfig unstated;
  EXPECT_FALSE(adopt_found_antenna(unstated, std::nullopt));
  EXPECT_FALSE(unstated.gnss_position_m.has_value());
  EXPECT_TRUE(adopt_found_antenna(unstated, Eigen::Vector2d(1.5, -0.2)));
  EXPECT_EQ(*unstated.gnss_position_m, Eigen::Vector2d(1.5, -0.2));

  VehicleConfig stated;
  stated.gnss_position_m = Eigen::Vector2d(0.3, 0.0);
  EXPECT_FALSE(adopt_found_antenna(stated, Eigen::Vector2d(1.5, -0.2)));
  EXPECT_EQ(*stated.gnss_position_m, Eigen::Vector2d(0.3, 0.0));
}

}  // namespace
}  // namespace odocal
