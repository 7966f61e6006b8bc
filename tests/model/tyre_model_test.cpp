// The tyre model's physical terms against closed-form loads and forces of a simple car (a body
// with no drag, equally stiff axles and an easy geometry): at rest, accelerating straight, braking,
// and in a steady left turn; the slip curve's bend and the front tyres' steer against the magic
// formula solved numerically.

#include "odocal/model/tyre_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace odocal {
namespace {

constexpr double g = 9.81;
constexpr int kLoad = 7, kDriving = 8, kBraking = 9;  // physical terms in TyreModel::Vector

// L = 2 m, half the weight on the rear axle, h = 0.5 m, the rear axle takes half the lateral
// transfer, t = 1.5 m, f_r = 0.01, no drag: a rear wheel carries g / 4 per vehicle mass at rest.
// Both axles' tyres equally stiff: at an even load they slip alike sideways, so the front wheels
// are steered by L w / v alone.
VehicleBody simple_body() {
  VehicleBody body;
  body.wheelbase_m = 2.0;
  body.track_width_m = 1.5;
  body.rear_axle_load_share = 0.5;
  body.cg_height_m = 0.5;
  body.rear_roll_share = 0.5;
  body.drag_area_m2 = 0.0;
  body.rolling_resistance = 0.01;
  body.front_cornering_stiffness = body.rear_cornering_stiffness = 18.0;
  return body;
}

// The slip over its linear part at force over grip x, from the magic formula itself:
// x = sin(C atan(s / C)) with s the slip in units of the linear slip's slope, solved by bisection
// below the curve's peak.
double magic_formula_bend(double x, double shape) {
  double low = 0.0, high = shape * std::tan(0.5 * std::numbers::pi / shape);  // the curve's peak
  for (int i = 0; i < 200; ++i) {
    const double s = 0.5 * (low + high);
    (std::sin(shape * std::atan(s / shape)) < x ? low : high) = s;
  }
  return 0.5 * (low + high) / x;
}

// The bend the regressors carry for the default brake share and a driven rear axle.
double driving_bend(double force_over_load) { return magic_formula_bend(force_over_load, 1.65); }
double braking_bend(double force_over_load) {
  return magic_formula_bend(0.35 * std::abs(force_over_load), 1.65);
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
    EXPECT_NEAR(x(kDriving), -0.02 * driving_bend(0.02), 1e-9);
    EXPECT_NEAR(x(kDriving), -0.02, 1e-5);  // a small force: the linear slip
    EXPECT_EQ(x(kBraking), 0.0);
  }
}

TEST(TyreModelPhysicalTerms, AcceleratingLoadsTheRearAxle) {
  // a_x = 2: each rear wheel gains h a_x / (2 L) = 0.25 per mass; force over load
  // ((2 + 0.0981) / 2) / (g / 4 + 0.25).
  const TyreModel::Vector x =
      tyre_regressors(state(10.0, 2.0, 0.0, 0.0), RearWheel::kLeft, simple_body());
  EXPECT_NEAR(x(kLoad), -0.25, 1e-6);
  const double rho = (1.0 + 0.5 * 0.01 * g) / (g / 4 + 0.25);
  EXPECT_NEAR(x(kDriving), -rho * driving_bend(rho), 1e-6);
  EXPECT_EQ(x(kBraking), 0.0);
}

TEST(TyreModelPhysicalTerms, BrakingSlipsTheOtherWay) {
  // a_x = -3: the rear wheels lose 0.375 per mass; the force is a brake force.
  const TyreModel::Vector x =
      tyre_regressors(state(10.0, -3.0, 0.0, 0.0), RearWheel::kRight, simple_body());
  EXPECT_NEAR(x(kLoad), 0.375, 1e-6);
  EXPECT_EQ(x(kDriving), 0.0);
  const double rho = (-1.5 + 0.5 * 0.01 * g) / (g / 4 - 0.375);
  EXPECT_NEAR(x(kBraking), -rho * braking_bend(rho), 1e-6);
  EXPECT_GT(x(kBraking), 0.0);  // a braked wheel turns slower: it covers more per revolution
}

TEST(TyreModelPhysicalTerms, ALeftTurnMovesLoadToTheRightWheel) {
  // a_y = 3 at w = 0.2 (v = 15): r h a_y / t = 0.5 moves from the left wheel to the right; the
  // front tyres' cornering drag b f_y w / v = 0.04 (both axles slip alike, so the front wheels
  // are steered along the path) adds to the tractive force; the unloaded left wheel slips more
  // for the same force.
  const VehicleBody body = simple_body();
  const DrivingState turn = state(15.0, 0.0, 3.0, 0.2);
  const TyreModel::Vector left = tyre_regressors(turn, RearWheel::kLeft, body);
  const TyreModel::Vector right = tyre_regressors(turn, RearWheel::kRight, body);
  EXPECT_NEAR(left(kLoad), 0.5, 1e-6);
  EXPECT_NEAR(right(kLoad), -0.5, 1e-6);
  const double force = 0.5 * (0.01 * g + 1.0 * 0.2 * 0.2);
  const double rho_left = force / (g / 4 - 0.5), rho_right = force / (g / 4 + 0.5);
  EXPECT_NEAR(left(kDriving), -rho_left * driving_bend(rho_left), 1e-6);
  EXPECT_NEAR(right(kDriving), -rho_right * driving_bend(rho_right), 1e-6);
  // The regression terms see the same turn through a_y alone, sided.
  EXPECT_NEAR(left(1), 3.0, 1e-6);
  EXPECT_NEAR(right(1), -3.0, 1e-6);
}

TEST(TyreModelPhysicalTerms, AnImuAheadOfTheCentreOfGravityIsTakenBackToIt) {
  // The simple body's centre of gravity is 1 m ahead of the rear axle. An IMU stated at (2.5,
  // 0.4) from the axle sits r = (1.5, 0.4) from it: at w = 0.2 and dw/dt = 0.5 it reads
  // -w^2 r + dw/dt x r = (-0.06 - 0.2, -0.016 + 0.75) beside the body's (2, 3). Taken back to the
  // centre of gravity, the regressors are the body's own; unstated, the reading is the body's.
  VehicleBody body = simple_body();
  DrivingState at_cg = state(15.0, 2.0, 3.0, 0.2);
  at_cg.yaw_acceleration_radps2 = 0.5f;
  DrivingState mounted = at_cg;
  mounted.specific_force_x_mps2 = static_cast<float>(2.0 - 0.2 * 0.2 * 1.5 - 0.5 * 0.4);
  mounted.specific_force_y_mps2 = static_cast<float>(3.0 + 0.5 * 1.5 - 0.2 * 0.2 * 0.4);
  EXPECT_NEAR(specific_force_at_cg(mounted, body).x(), mounted.specific_force_x_mps2, 1e-12);
  body.imu_position_m = Eigen::Vector2d(2.5, 0.4);
  const Eigen::Vector2d back = specific_force_at_cg(mounted, body);
  EXPECT_NEAR(back.x(), 2.0, 1e-6);
  EXPECT_NEAR(back.y(), 3.0, 1e-6);
  for (const RearWheel wheel : {RearWheel::kLeft, RearWheel::kRight}) {
    const TyreModel::Vector expected = tyre_regressors(at_cg, wheel, simple_body());
    EXPECT_LT((tyre_regressors(mounted, wheel, body) - expected).cwiseAbs().maxCoeff(), 1e-5);
  }
  EXPECT_NEAR(side_slip_regressor(mounted, body), 3.0, 1e-6);
}

TEST(TyreModelPhysicalTerms, AForceTheLogGivesIsTheTyresInPlaceOfTheAccelerometers) {
  // Accelerating at 2 m/s^2 in a left turn at 10 m/s (0.3 rad/s): the car of 1500 kg pushes
  // m (2 + f_r g + the cornering drag) through its tyres (no drag on this body). Given that force,
  // the accelerometer's forward reading is not read: the regressors are those of the reading the
  // force implies.
  const VehicleBody body = simple_body();
  DrivingState given = state(10.0, 2.0, 3.0, 0.3);
  given.specific_force_x_mps2 = -7.0f;  // a forward reading far off
  const DrivingState read = state(10.0, 2.0, 3.0, 0.3);
  given.drive_force_n = static_cast<float>(
      body.mass_kg * (2.0 + 0.01 * kGravityMps2 + cornering_drag_mps2(read, body)));
  for (const RearWheel wheel : {RearWheel::kLeft, RearWheel::kRight}) {
    const TyreModel::Vector with_force = tyre_regressors(given, wheel, body);
    const TyreModel::Vector with_reading = tyre_regressors(read, wheel, body);
    // The regression terms keep the wheels' own acceleration, as they did.
    for (int j = 0; j < TyreModel::kCoefficients; ++j)
      EXPECT_NEAR(with_force(j), with_reading(j), 1e-6) << j;
    EXPECT_NE(with_force(kLoad), tyre_regressors(state(10.0, -7.0, 3.0, 0.3), wheel, body)(kLoad));
  }
  // A force that brakes slips the other way, whatever the accelerometer reads.
  given.drive_force_n = -3000.0f;
  given.specific_force_x_mps2 = 2.0f;
  const TyreModel::Vector braking = tyre_regressors(given, RearWheel::kLeft, body);
  EXPECT_EQ(braking(kDriving), 0.0);
  EXPECT_GT(braking(kBraking), 0.0);
}

// A wheel cannot carry more than its grip: past it, its slip regressor stays at the grip (0.99 mu
// over its axle's share of the force), as the magic formula's slip at its end, however much the
// car demands; below it, nothing is held.
TEST(TyreModelPhysicalTerms, AWheelPastItsGripSlipsAsAtItsGrip) {
  // A lifted inner wheel (a tenth of its load kept) in a hard left turn under power.
  const TyreModel::Vector lifted =
      tyre_regressors(state(20.0, 1.0, 20.0, 1.0), RearWheel::kLeft, simple_body());
  EXPECT_NEAR(lifted(kDriving), -0.99 * driving_bend(0.99), 1e-9);
  // Braking at 12 m/s^2 straight: the rear brakes' 0.35 of the car's force is past the grip.
  const TyreModel::Vector locked =
      tyre_regressors(state(20.0, -12.0, 0.0, 0.0), RearWheel::kLeft, simple_body());
  EXPECT_NEAR(locked(kBraking), 0.99 / 0.35 * braking_bend(0.99 / 0.35), 1e-9);
  // Short of the grip: the force over load itself.
  const TyreModel::Vector gentle =
      tyre_regressors(state(20.0, -3.0, 0.0, 0.0), RearWheel::kLeft, simple_body());
  const double rho = (-1.5 + 0.5 * 0.01 * g) / (g / 4 - 0.375);
  EXPECT_NEAR(gentle(kBraking), -rho * braking_bend(rho), 1e-6);
}

TEST(TyreModelSlipCurve, BendIsTheMagicFormulasInverse) {
  const VehicleBody body;
  for (const double x : {1e-3, 0.1, 0.3, 0.5, 0.75, 0.9, 0.99})
    EXPECT_NEAR(slip_curve_bend(x, body), magic_formula_bend(x, 1.65), 1e-9) << x;
  EXPECT_NEAR(slip_curve_bend(0.75, body), 1.242, 1e-3);  // docs/tyre-model.md
  EXPECT_EQ(slip_curve_bend(0.0, body), 1.0);
  EXPECT_EQ(slip_curve_bend(-0.5, body), slip_curve_bend(0.5, body));  // braking as driving
  EXPECT_EQ(slip_curve_bend(5.0, body), slip_curve_bend(0.99, body));  // held below the grip
}

TEST(TyreModelSlipCurve, LessGripBendsTheSameForceMore) {
  VehicleBody wet;
  wet.friction = 0.5;
  EXPECT_NEAR(slip_curve_bend(0.3, wet), magic_formula_bend(0.6, 1.65), 1e-9);
  VehicleBody later;
  later.slip_curve_shape = 1.9;
  EXPECT_NEAR(slip_curve_bend(0.6, later), magic_formula_bend(0.6, 1.9), 1e-9);
  // A larger C bends less below the peak: 1 + (1 / 6 + 1 / (3 C^2)) x^2 + ...
  EXPECT_LT(slip_curve_bend(0.6, later), slip_curve_bend(0.6, VehicleBody{}));
}

TEST(TyreModelSlipCurve, EachAxleBendsWithItsOwnShareOfTheForce) {
  // Braking at 3 m/s^2: the bend is taken at the rear brakes' share of the force over load.
  VehicleBody body = simple_body();
  body.brake_rear_share = 0.5;
  const DrivingState braking = state(10.0, -3.0, 0.0, 0.0);
  const double rho = (-1.5 + 0.5 * 0.01 * g) / (g / 4 - 0.375);
  EXPECT_NEAR(tyre_regressors(braking, RearWheel::kLeft, body)(kBraking),
              -rho * magic_formula_bend(0.5 * std::abs(rho), 1.65), 1e-6);
  // A front-driven car's rear wheels carry none of the drive: no bend on the driving term, whose
  // coefficient the batch holds at zero.
  body.drivetrain = Drivetrain::kFront;
  const DrivingState accelerating = state(10.0, 2.0, 0.0, 0.0);
  const double driving = (1.0 + 0.5 * 0.01 * g) / (g / 4 + 0.25);
  EXPECT_NEAR(tyre_regressors(accelerating, RearWheel::kLeft, body)(kDriving), -driving, 1e-6);
  // All-wheel drive: the rear axle's share of it.
  body.drivetrain = Drivetrain::kAll;
  body.all_wheel_drive_rear_share = 0.6;
  EXPECT_NEAR(tyre_regressors(accelerating, RearWheel::kLeft, body)(kDriving),
              -driving * magic_formula_bend(0.6 * driving, 1.65), 1e-6);
}

// The slip angle at which a tyre of cornering stiffness C_a per load carries the lateral force
// over load y: the lateral magic formula y = mu sin(C atan(B alpha)), B = C_a / (C mu), solved by
// bisection below its peak.
double lateral_slip_angle(double y, double stiffness, const VehicleBody& body) {
  const double c = body.lateral_curve_shape, mu = body.friction, b = stiffness / (c * mu);
  const double sign = y < 0.0 ? -1.0 : 1.0;
  double low = 0.0, high = std::tan(0.5 * std::numbers::pi / c) / b;
  for (int i = 0; i < 200; ++i) {
    const double alpha = 0.5 * (low + high);
    (mu * std::sin(c * std::atan(b * alpha)) < std::abs(y) ? low : high) = alpha;
  }
  return sign * 0.5 * (low + high);
}

TEST(TyreModelSteer, SlipAngleIsTheLateralMagicFormulasInverse) {
  VehicleBody body;
  for (const double y : {-0.6, 0.01, 0.3, 0.6, 0.9})
    EXPECT_NEAR(slip_angle_rad(y, 16.0, body), lateral_slip_angle(y, 16.0, body), 1e-9) << y;
  EXPECT_NEAR(slip_angle_rad(0.01, 16.0, body), 0.01 / 16.0, 1e-7);  // the linear part: y / C_a
  EXPECT_EQ(slip_angle_rad(3.0, 16.0, body), slip_angle_rad(0.99, 16.0, body));  // at its grip
  body.friction = 0.5;
  EXPECT_NEAR(slip_angle_rad(0.4, 19.0, body), lateral_slip_angle(0.4, 19.0, body), 1e-9);
}

TEST(TyreModelSteer, AxlesThatSlipAlikeSteerTheFrontWheelsAlongThePath) {
  // The steady left turn at 15 m/s, 0.2 rad/s, 3 m/s^2: the front axle's b / L of the lateral
  // force along wheels steered by L w / v, b f_y w / v = 0.04 m/s^2.
  EXPECT_NEAR(cornering_drag_mps2(state(15.0, 0.0, 3.0, 0.2), simple_body()), 0.04, 1e-9);
}

TEST(TyreModelSteer, AnUndersteeringCarSteersBeyondThePath) {
  // The rear tyres stiffer: at an even load (f_y / g on both axles) the front slips more sideways
  // than the rear, and the front wheels are steered by that much beyond L w / v.
  VehicleBody body = simple_body();
  body.front_cornering_stiffness = 16.0;
  body.rear_cornering_stiffness = 19.0;
  const double f_y = 6.0, w = 0.3, v = 20.0;
  const double steer = 2.0 * w / v + lateral_slip_angle(f_y / g, 16.0, body) -
                       lateral_slip_angle(f_y / g, 19.0, body);
  EXPECT_NEAR(cornering_drag_mps2(state(v, 0.0, f_y, w), body), 0.5 * f_y * steer,
              1e-7);  // w a float
  EXPECT_GT(steer, 2.0 * w / v);
}

TEST(TyreModelSteer, AFishtailTurnsTheFrontForceAgainstTheYawInertia) {
  // No lateral force and no turn, but the yaw rate growing at 1 rad/s^2: with I_z = m a b the
  // front axle pushes m a b / L = m / 2 left and the rear as much right; the front tyres' slip
  // angle at 0.5 over their load g / 2 and the rear's at -0.5 over theirs steer the front wheels
  // by twice the one angle, along which the front force drags.
  DrivingState fishtail = state(20.0, 0.0, 0.0, 0.0);
  fishtail.yaw_acceleration_radps2 = 1.0f;
  const VehicleBody body = simple_body();
  const double alpha = lateral_slip_angle(1.0 / g, 18.0, body);
  EXPECT_NEAR(cornering_drag_mps2(fishtail, body), 0.5 * 2.0 * alpha, 1e-9);
  EXPECT_GT(alpha, 0.0);
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
