// A car's spread of its physical tyre coefficients, and the spread about zero of one held there,
// against closed forms: the radius's load sensitivity over the wheel radius, and two Gaussian
// statements of one number combined.

#include "odocal/model/tyre_car_prior.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace odocal {
namespace {

constexpr int kLoad = 7, kDriving = 8, kBraking = 9, kSideSlip = 10;

TEST(TyreCarPrior, IsACarsSizeOfEachPhysicalCoefficient) {
  VehicleBody body;
  body.mass_kg = 1500.0;
  const double circumference = 2.0 * std::numbers::pi * 0.31;
  // 0.4 mm per kN times 1500 kg over a 0.31 m radius.
  EXPECT_NEAR(car_tyre_coefficient_sigma(kLoad, body, circumference), 0.4e-6 * 1500.0 / 0.31,
              1e-12);
  body.mass_kg = 3000.0;
  EXPECT_NEAR(car_tyre_coefficient_sigma(kLoad, body, circumference), 2 * 0.4e-6 * 1500.0 / 0.31,
              1e-12);
  // The drive slip by drivetrain: unstated, a driven rear axle's.
  EXPECT_DOUBLE_EQ(car_tyre_coefficient_sigma(kDriving, body, circumference), 1.0 / 20.0);
  body.drivetrain = Drivetrain::kRear;
  EXPECT_DOUBLE_EQ(car_tyre_coefficient_sigma(kDriving, body, circumference), 1.0 / 20.0);
  body.drivetrain = Drivetrain::kAll;
  EXPECT_DOUBLE_EQ(car_tyre_coefficient_sigma(kDriving, body, circumference), 0.5 / 20.0);
  body.drivetrain = Drivetrain::kFront;
  EXPECT_DOUBLE_EQ(car_tyre_coefficient_sigma(kDriving, body, circumference), 0.05 / 20.0);
  EXPECT_DOUBLE_EQ(car_tyre_coefficient_sigma(kBraking, body, circumference), 0.35 / 20.0);
  EXPECT_NEAR(car_tyre_coefficient_sigma(kSideSlip, body, circumference), 1.0 / (9.81 * 19.0),
              1e-12);
  for (int j = 0; j < 7; ++j)
    EXPECT_EQ(car_tyre_coefficient_sigma(j, body, circumference), 0.0) << "regression term " << j;
  EXPECT_EQ(car_tyre_coefficient_sigma(-1, body, circumference), 0.0);
  EXPECT_EQ(car_tyre_coefficient_sigma(TyreModel::kCoefficients, body, circumference), 0.0);
}

TEST(TyreCarPrior, AHeldCoefficientsSpreadCombinesTheLogsWordWithTheCars) {
  const double inf = std::numeric_limits<double>::infinity();
  // The log said nothing: the car's spread.
  EXPECT_DOUBLE_EQ(held_coefficient_sigma(0.3, inf, 0.02), 0.02);
  EXPECT_DOUBLE_EQ(held_coefficient_sigma(std::nan(""), 0.01, 0.02), 0.02);
  // Equal sigmas at zero: the combined sigma, 1/sqrt(2) of either.
  EXPECT_NEAR(held_coefficient_sigma(0.0, 0.02, 0.02), 0.02 / std::sqrt(2.0), 1e-15);
  // Equal sigmas, the log at 0.02: the mean halfway, 0.01, beside the same variance.
  EXPECT_NEAR(held_coefficient_sigma(0.02, 0.02, 0.02), std::sqrt(1e-4 + 2e-4), 1e-15);
  // A log far surer than the car: its own estimate and sigma about zero.
  EXPECT_NEAR(held_coefficient_sigma(3e-4, 1e-4, 1.0), std::hypot(3e-4, 1e-4), 1e-10);
  // The sign of the estimate does not matter; no car spread (a regression term): nothing.
  EXPECT_DOUBLE_EQ(held_coefficient_sigma(-0.01, 0.01, 0.02),
                   held_coefficient_sigma(0.01, 0.01, 0.02));
  EXPECT_EQ(held_coefficient_sigma(0.01, 0.01, 0.0), 0.0);
}

}  // namespace
}  // namespace odocal
