// Path geometry against closed forms, and the driver's speed profile against its limits.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "odocal/io/scenario_io.hpp"
#include "odocal/sim/path.hpp"
#include "odocal/sim/simulator.hpp"
#include "odocal/sim/speed_profile.hpp"

namespace odocal::sim {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(Path, QuarterArcEndsWhereGeometrySays) {
  const double radius = 20.0;
  const Path path({{radius * kPi / 2, 1 / radius, 1 / radius, 1}}, Pose2(1.0, 2.0, 0.0));
  const PathPoint end = path.at(path.length_m());
  EXPECT_NEAR(end.pose.x(), 1.0 + radius, 1e-9);
  EXPECT_NEAR(end.pose.y(), 2.0 + radius, 1e-9);
  EXPECT_NEAR(end.pose.z(), kPi / 2, 1e-12);
  const PathPoint middle = path.at(path.length_m() / 2);  // between grid points: still on the arc
  EXPECT_NEAR(std::hypot(middle.pose.x() - 1.0, middle.pose.y() - 2.0 - radius), radius, 1e-9);
}

TEST(Path, ClothoidYawIsTheIntegralOfCurvature) {
  const Path path({{50.0, 0.0, 0.04, 1}}, Pose2::Zero());
  EXPECT_NEAR(path.at(50.0).pose.z(), 0.5 * 0.04 * 50.0, 1e-12);
  EXPECT_NEAR(path.at(25.0).pose.z(), 0.5 * 0.02 * 25.0, 1e-12);
  EXPECT_NEAR(path.at(25.0).curvature_1pm, 0.02, 1e-12);
}

TEST(Path, ReversingMovesBackwardsAndCountsNegativeDistance) {
  // Backing 10 m while the yaw grows by 90 deg: the rear swings to the right of the start.
  const double radius = 10.0 / (kPi / 2);
  const Path path({{10.0, -1 / radius, -1 / radius, -1}}, Pose2::Zero());
  const PathPoint end = path.at(10.0);
  EXPECT_NEAR(end.signed_distance_m, -10.0, 1e-12);
  EXPECT_NEAR(end.pose.z(), kPi / 2, 1e-12);
  EXPECT_NEAR(end.pose.x(), -radius, 1e-9);
  EXPECT_NEAR(end.pose.y(), -radius, 1e-9);
  EXPECT_EQ(path.direction_changes_m().size(), 0u);
}

TEST(Path, BuiltInCircuitClosesAfterEachLap) {
  Scenario scenario = load_scenario("circuit");
  scenario.route.laps = 1;
  const Path path = route_path(scenario);
  EXPECT_NEAR(path.length_m(), 4521.4, 1.0);
  const PathPoint end = path.at(path.length_m());
  EXPECT_LT(end.pose.head<2>().norm(), 1e-6);
  EXPECT_NEAR(end.pose.z(), 2 * kPi, 1e-9);
}

TEST(SpeedProfile, RespectsLimitsAndStops) {
  Scenario scenario = load_scenario("urban");
  const Path path = route_path(scenario);
  const DriverLimits limits = scenario.driver;
  const SpeedProfile profile(path, limits, {{200.0, 10.0}});
  double previous_speed = 0.0;
  bool stopped_at_200 = false;
  const double dt = 0.05;
  for (double t = 0.0; t <= profile.duration_s(); t += dt) {
    const MotionState state = profile.at(t);
    const PathPoint point = path.at(state.s_m);
    EXPECT_LE(state.speed_mps, limits.max_speed_mps + 1e-9);
    // Lateral limit holds at grid points and between them up to the grid's curvature change.
    EXPECT_LE(state.speed_mps * state.speed_mps * std::abs(point.curvature_1pm),
              limits.max_lateral_acc_mps2 * 1.05 + 0.5)
        << t;
    EXPECT_LE((state.speed_mps - previous_speed) / dt, limits.max_acc_mps2 + 1e-6);
    EXPECT_GE((state.speed_mps - previous_speed) / dt, -limits.max_brake_mps2 - 1e-6);
    if (std::abs(state.s_m - 200.0) < 0.5 && state.speed_mps == 0.0) stopped_at_200 = true;
    previous_speed = state.speed_mps;
  }
  EXPECT_TRUE(stopped_at_200);
  EXPECT_DOUBLE_EQ(profile.at(profile.duration_s()).s_m, path.length_m());
}

// The profile's speed where it first reaches s_m (sampled every millisecond).
double speed_at_distance(const SpeedProfile& profile, double s_m) {
  for (double t = 0.0; t <= profile.duration_s(); t += 1e-3) {
    const MotionState state = profile.at(t);
    if (state.s_m >= s_m) return state.speed_mps;
  }
  return profile.at(profile.duration_s()).speed_mps;
}

// From rest on a circle of radius R, a driver who gives the acceleration only the grip the turn
// leaves, a_x = a sqrt(1 - u^2) with u = v^2 / (R a_y,max), has du/ds = (2 a / (R a_y,max))
// sqrt(1 - u^2): u = sin(2 a s / (R a_y,max)), the corner speed at s = pi R a_y,max / (4 a).
TEST(SpeedProfile, AFrictionEllipseDriverLeavesTheTurnItsGrip) {
  const double radius = 100.0;
  const Path circle({{2 * kPi * radius, 1 / radius, 1 / radius, 1}}, Pose2::Zero());
  DriverLimits limits;
  limits.max_lateral_acc_mps2 = 4.0;
  limits.max_acc_mps2 = 3.0;
  limits.max_brake_mps2 = 5.0;
  limits.friction_ellipse = true;
  const SpeedProfile profile(circle, limits, {});
  const double scale = 2 * limits.max_acc_mps2 / (radius * limits.max_lateral_acc_mps2);
  for (const double s : {10.0, 40.0, 80.0}) {
    const double expected = std::sqrt(radius * limits.max_lateral_acc_mps2 * std::sin(scale * s));
    EXPECT_NEAR(speed_at_distance(profile, s), expected, 0.01 * expected) << s;
  }
  // Without it the same driver reaches the corner speed sooner, at full acceleration.
  limits.friction_ellipse = false;
  const SpeedProfile separate(circle, limits, {});
  EXPECT_NEAR(speed_at_distance(separate, 40.0), std::sqrt(2 * limits.max_acc_mps2 * 40.0), 0.1);
  // On a straight the ellipse changes nothing.
  const Path straight({{500.0, 0.0, 0.0, 1}}, Pose2::Zero());
  limits.friction_ellipse = true;
  const SpeedProfile ellipse_straight(straight, limits, {});
  limits.friction_ellipse = false;
  const SpeedProfile plain_straight(straight, limits, {});
  EXPECT_DOUBLE_EQ(ellipse_straight.duration_s(), plain_straight.duration_s());
}

// Above P / a_max the power limits the acceleration, a = P / v: d(v^2)/dt = 2 P, so v^2 grows
// linearly in time from where the power takes over.
TEST(SpeedProfile, APowerLimitedDriverGainsSpeedSquaredLinearlyInTime) {
  const Path straight({{2000.0, 0.0, 0.0, 1}}, Pose2::Zero());
  DriverLimits limits;
  limits.max_speed_mps = 45.0;
  limits.max_acc_mps2 = 3.0;
  limits.max_power_wpkg = 80.0;  // 120 kW for 1500 kg
  const SpeedProfile profile(straight, limits, {});
  const double takeover_mps = limits.max_power_wpkg / limits.max_acc_mps2;
  const double takeover_s = limits.start_dwell_s + takeover_mps / limits.max_acc_mps2;
  for (const double after_s : {1.0, 3.0, 5.0}) {
    const double expected =
        std::sqrt(takeover_mps * takeover_mps + 2 * limits.max_power_wpkg * after_s);
    EXPECT_NEAR(profile.at(takeover_s + after_s).speed_mps, expected, 0.01 * expected) << after_s;
  }
  EXPECT_NEAR(profile.at(takeover_s - 1.0).speed_mps, takeover_mps - limits.max_acc_mps2, 0.05);
}

}  // namespace
}  // namespace odocal::sim
