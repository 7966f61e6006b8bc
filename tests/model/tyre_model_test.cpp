// The tyre model's physical terms against closed-form loads and forces of a simple car (a body
// with no drag, no cornering drag and an easy geometry): at rest, accelerating straight, braking,
// and in a steady left turn.

#include "odocal/model/tyre_model.hpp"

#include <gtest/gtest.h>

namespace odocal {
namespace {

constexpr double g = 9.81;
constexpr int kLoad = 7, kDriving = 8, kBraking = 9;  // physical terms in TyreModel::Vector

// L = 2 m, half the weight on the rear axle, h = 0.5 m, the rear axle takes half the lateral
// transfer, t = 1.5 m, f_r = 0.01, no drag: a rear wheel carries g / 4 per vehicle mass at rest.
VehicleBody simple_body() {
  VehicleBody body;
  body.wheelbase_m = 2.0;
  body.track_width_m = 1.5;
  body.rear_axle_load_share = 0.5;
  body.cg_height_m = 0.5;
  body.rear_roll_share = 0.5;
  body.drag_area_m2 = 0.0;
  body.rolling_resistance = 0.01;
  return body;
}

DrivingState state(double speed, double f_x, double f_y, double yaw_rate) {
  DrivingState s;
  s.speed_mps = static_cast<float>(speed);
  s.yaw_rate_radps = static_cast<float>(yaw_rate);
  s.specific_force_x_mps2 = static_cast<float>(f_x);
  s.specific_force_y_mps2 = static_cast<float>(f_y);
  s.longitudinal_mps2 = s.specific_force_x_mps2;
  return s;
}

TEST(TyreModelPhysicalTerms, RollingResistanceAloneAtConstantSpeed) {
  // Force over load: (f_r g / 2) / (g / 4) = 2 f_r on either wheel; no load change.
  for (const RearWheel wheel : {RearWheel::kLeft, RearWheel::kRight}) {
    const TyreModel::Vector x = tyre_regressors(state(10.0, 0.0, 0.0, 0.0), wheel, simple_body());
    EXPECT_NEAR(x(kLoad), 0.0, 1e-12);
    EXPECT_NEAR(x(kDriving), -0.02, 1e-9);
    EXPECT_EQ(x(kBraking), 0.0);
  }
}

TEST(TyreModelPhysicalTerms, AcceleratingLoadsTheRearAxle) {
  // a_x = 2: each rear wheel gains h a_x / (2 L) = 0.25 per mass; force over load
  // ((2 + 0.0981) / 2) / (g / 4 + 0.25).
  const TyreModel::Vector x =
      tyre_regressors(state(10.0, 2.0, 0.0, 0.0), RearWheel::kLeft, simple_body());
  EXPECT_NEAR(x(kLoad), -0.25, 1e-6);
  EXPECT_NEAR(x(kDriving), -(1.0 + 0.5 * 0.01 * g) / (g / 4 + 0.25), 1e-6);
  EXPECT_EQ(x(kBraking), 0.0);
}

TEST(TyreModelPhysicalTerms, BrakingSlipsTheOtherWay) {
  // a_x = -3: the rear wheels lose 0.375 per mass; the force is a brake force.
  const TyreModel::Vector x =
      tyre_regressors(state(10.0, -3.0, 0.0, 0.0), RearWheel::kRight, simple_body());
  EXPECT_NEAR(x(kLoad), 0.375, 1e-6);
  EXPECT_EQ(x(kDriving), 0.0);
  EXPECT_NEAR(x(kBraking), -(-1.5 + 0.5 * 0.01 * g) / (g / 4 - 0.375), 1e-6);
  EXPECT_GT(x(kBraking), 0.0);  // a braked wheel turns slower: it covers more per revolution
}

TEST(TyreModelPhysicalTerms, ALeftTurnMovesLoadToTheRightWheel) {
  // a_y = 3 at w = 0.2 (v = 15): r h a_y / t = 0.5 moves from the left wheel to the right; the
  // front tyres' cornering drag b w^2 = 0.04 adds to the tractive force; the unloaded left wheel
  // slips more for the same force.
  const VehicleBody body = simple_body();
  const DrivingState turn = state(15.0, 0.0, 3.0, 0.2);
  const TyreModel::Vector left = tyre_regressors(turn, RearWheel::kLeft, body);
  const TyreModel::Vector right = tyre_regressors(turn, RearWheel::kRight, body);
  EXPECT_NEAR(left(kLoad), 0.5, 1e-6);
  EXPECT_NEAR(right(kLoad), -0.5, 1e-6);
  const double force = 0.5 * (0.01 * g + 1.0 * 0.2 * 0.2);
  EXPECT_NEAR(left(kDriving), -force / (g / 4 - 0.5), 1e-6);
  EXPECT_NEAR(right(kDriving), -force / (g / 4 + 0.5), 1e-6);
  // The regression terms see the same turn through a_y alone, sided.
  EXPECT_NEAR(left(1), 3.0, 1e-6);
  EXPECT_NEAR(right(1), -3.0, 1e-6);
}

TEST(TyreModelPhysicalTerms, ALiftedWheelKeepsATenthOfItsLoad) {
  const TyreModel::Vector x =
      tyre_regressors(state(20.0, 1.0, 20.0, 1.0), RearWheel::kLeft, simple_body());
  const double force = 0.5 * (1.0 + 0.01 * g + 1.0 * 1.0 * 1.0);
  EXPECT_NEAR(x(kDriving), -force / (0.1 * g / 4), 1e-5);
}

TEST(TyreModel, CoefficientTableRoundTripsEveryMember) {
  TyreModel::Vector k;
  for (int j = 0; j < TyreModel::kCoefficients; ++j) k(j) = 0.001 * (j + 1);
  const TyreModel model = TyreModel::from(k);
  EXPECT_EQ(model.coefficients(), k);
  EXPECT_EQ(model.k_speed_s2pm2, 0.001);
  EXPECT_EQ(model.k_brake_slip, 0.010);
  EXPECT_EQ(model.k_side_slip_s2pm, 0.011);
  EXPECT_EQ(kTyreCoefficients[kSideSlipCoefficient].member, &TyreModel::k_side_slip_s2pm);
  EXPECT_FALSE(model.plain());
  EXPECT_TRUE(TyreModel{}.plain());
  for (const TyreCoefficient& c : kTyreCoefficients) EXPECT_LT(c.min, c.max) << c.key;
}

}  // namespace
}  // namespace odocal
