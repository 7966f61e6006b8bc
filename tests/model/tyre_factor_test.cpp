// The rolling factor c_eff / c that the tyre model applies: against the simulator's own steady
// rolling radius (an independent implementation of the same tyre), its gradient against central
// differences, and its guard against a solver's absurd trial coefficients.

#include <gtest/gtest.h>

#include <cmath>

#include "odocal/model/tyre_model.hpp"
#include "odocal/sim/vehicle_dynamics.hpp"

namespace odocal {
namespace {

DrivingState straight(double speed_mps) {
  DrivingState s;
  s.speed_mps = static_cast<float>(speed_mps);
  return s;
}

DrivingState turning(double speed_mps, double f_x, double f_y) {
  DrivingState s = straight(speed_mps);
  s.longitudinal_mps2 = static_cast<float>(f_x);
  s.specific_force_x_mps2 = static_cast<float>(f_x);
  s.specific_force_y_mps2 = static_cast<float>(f_y);
  s.yaw_rate_radps = static_cast<float>(f_y / speed_mps);
  return s;
}

TEST(TyreFactor, IsTheSimulatorsSteadyRollingRadiusOfItsOwnTyre) {
  // The simulator's default car and tyre, stated as the body; k_drive_slip = 1 / C_kappa on a
  // rear-driven car. Straight at a steady speed its rear wheels push the drag and the rolling
  // resistance, and roll at r / (1 + kappa).
  const sim::VehicleDynamicsConfig config;
  const sim::StaticRearRadii radii{0.31, 0.31};
  VehicleBody body;
  body.drivetrain = Drivetrain::kRear;
  body.rear_axle_load_share = config.cg_to_front_axle_m / body.wheelbase_m;
  body.mass_kg = config.mass_kg;
  body.drag_area_m2 = config.drag_area_m2;
  body.rolling_resistance = config.rolling_resistance;
  body.friction = config.friction;
  body.slip_curve_shape = config.longitudinal_shape;
  TyreModel tyre;
  tyre.k_drive_slip = 1.0 / config.slip_stiffness_per_load;
  for (const double speed : {5.0, 30.0, 50.0}) {
    const double simulated =
        sim::steady_rolling_radii_m(config, body.wheelbase_m, body.track_width_m, radii, speed)[0] /
        radii.rl_m;
    const double factor = tyre_factor(tyre, straight(speed), RearWheel::kLeft, body);
    EXPECT_NEAR(factor, simulated, 1e-9) << speed;
    // The linear form 1 - kappa that odocal used before misses kappa^2: 1.6e-5 at 30 m/s.
    const double kappa = 1.0 / simulated - 1.0;
    if (speed >= 30.0) {
      EXPECT_GT(std::abs(1.0 - kappa - simulated), 1e-5) << speed;
    }
  }
}

TEST(TyreFactor, GradientMatchesCentralDifferences) {
  const VehicleBody body;
  const TyreModel::Vector at =
      TyreModel{2e-6, 3e-4, 8e-3, -2e-3, -5e-3, 6e-4, 4e-4, 2e-3, 0.05, 0.02, -5e-3}.coefficients();
  for (const DrivingState& state : {turning(20.0, 2.5, 4.0), turning(15.0, -6.0, -3.0)}) {
    for (const RearWheel wheel : {RearWheel::kLeft, RearWheel::kRight}) {
      const TyreFactor f = tyre_factor_with_gradient(TyreModel::from(at), state, wheel, body);
      for (int j = 0; j < TyreModel::kCoefficients; ++j) {
        const double h = 1e-6;
        TyreModel::Vector up = at, down = at;
        up(j) += h;
        down(j) -= h;
        const double numerical = (tyre_factor(TyreModel::from(up), state, wheel, body) -
                                  tyre_factor(TyreModel::from(down), state, wheel, body)) /
                                 (2.0 * h);
        EXPECT_NEAR(f.gradient(j), numerical, 1e-7 * std::max(1.0, std::abs(numerical))) << j;
      }
      // The slip divides: with the slip terms alone the factor is 1 / (1 + kappa).
      TyreModel::Vector slip_only = TyreModel::Vector::Zero();
      slip_only(kDriveSlipCoefficient) = at(kDriveSlipCoefficient);
      slip_only(kBrakeSlipCoefficient) = at(kBrakeSlipCoefficient);
      const double kappa = -slip_only.dot(tyre_regressors(state, wheel, body));
      EXPECT_GT(std::abs(kappa), 1e-3);
      EXPECT_NEAR(tyre_factor(TyreModel::from(slip_only), state, wheel, body), 1.0 / (1.0 + kappa),
                  1e-12);
    }
  }
}

TEST(TyreFactor, BothWheelsAtOnceAreEachWheelAlone) {
  // rear_tyre_factors_with_gradient shares the state's axle forces (and its cornering drag's
  // fixed point) between the wheels: the same numbers, with the accelerometer or a given force.
  const VehicleBody body;
  const TyreModel tyre =
      TyreModel{2e-6, 3e-4, 8e-3, -2e-3, -5e-3, 6e-4, 4e-4, 2e-3, 0.05, 0.02, -5e-3};
  DrivingState given = turning(25.0, 1.5, -5.0);
  given.drive_force_n = 4000.0f;
  for (const DrivingState& state : {turning(20.0, 2.5, 4.0), turning(15.0, -6.0, -3.0), given}) {
    const RearTyreFactors both = rear_tyre_factors_with_gradient(tyre, state, body);
    const TyreFactor left = tyre_factor_with_gradient(tyre, state, RearWheel::kLeft, body);
    const TyreFactor right = tyre_factor_with_gradient(tyre, state, RearWheel::kRight, body);
    EXPECT_EQ(both.left.value, left.value);
    EXPECT_EQ(both.right.value, right.value);
    EXPECT_EQ(both.left.gradient, left.gradient);
    EXPECT_EQ(both.right.gradient, right.gradient);
    EXPECT_NE(left.value, right.value);  // the turn loads one wheel and lifts the other
  }
}

TEST(TyreFactor, AnAbsurdTrialSlipStaysFiniteAndPositive) {
  // A solver may try the bounds: a braking slip coefficient of 1 on a hard stop would make
  // kappa beyond -1 and the wheel's circumference infinite or negative; the slip is held at half
  // the wheel's speed, where it is locked anyway.
  TyreModel tyre;
  tyre.k_brake_slip = 1.0;
  const DrivingState stop = turning(20.0, -9.0, 6.0);
  const TyreFactor f = tyre_factor_with_gradient(tyre, stop, RearWheel::kLeft, VehicleBody{});
  EXPECT_DOUBLE_EQ(f.value, 2.0);
  EXPECT_EQ(f.gradient(kBrakeSlipCoefficient), 0.0);
}

}  // namespace
}  // namespace odocal
