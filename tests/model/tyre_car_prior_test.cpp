// A car's physical tyre coefficients, and the spread of one held at a value, against closed
// forms: the radius's load sensitivity over the wheel radius, the slip stiffness and the
// drivetrain's share of the drive, and two Gaussian statements of one number combined.

#include "odocal/model/tyre_car_prior.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace odocal {
namespace {

constexpr int kLoad = 7, kDriving = 8, kBraking = 9, kSideSlip = 10;

TEST(TyreCarPrior, IsACarsValueOfEachPhysicalCoefficientWithItsSignAndSize) {
  VehicleBody body;
  body.mass_kg = 1500.0;
  const double circumference = 2.0 * std::numbers::pi * 0.31;
  const auto car = [&](int j) { return car_tyre_coefficient(j, body, circumference); };
  // 0.4 mm per kN times 1500 kg over a 0.31 m radius: the radius shrinks under load.
  EXPECT_NEAR(car(kLoad).mean, 0.4e-6 * 1500.0 / 0.31, 1e-12);
  EXPECT_EQ(car(kLoad).sigma, car(kLoad).mean);
  body.mass_kg = 3000.0;
  EXPECT_NEAR(car(kLoad).mean, 2 * 0.4e-6 * 1500.0 / 0.31, 1e-12);
  // The drive slip by drivetrain: unstated, none expected and a driven axle's sigma.
  EXPECT_EQ(car(kDriving).mean, 0.0);
  EXPECT_DOUBLE_EQ(car(kDriving).sigma, 1.0 / 20.0);
  body.drivetrain = Drivetrain::kRear;
  EXPECT_DOUBLE_EQ(car(kDriving).mean, 1.0 / 20.0);
  EXPECT_DOUBLE_EQ(car(kDriving).sigma, 1.0 / 20.0);
  body.drivetrain = Drivetrain::kAll;  // the body's share of the drive on the rear axle
  EXPECT_DOUBLE_EQ(car(kDriving).mean, 0.6 / 20.0);
  body.all_wheel_drive_rear_share = 0.5;
  EXPECT_DOUBLE_EQ(car(kDriving).mean, 0.5 / 20.0);
  body.drivetrain = Drivetrain::kFront;
  EXPECT_EQ(car(kDriving).mean, 0.0);
  EXPECT_DOUBLE_EQ(car(kDriving).sigma, 0.01 / 20.0);  // the model's slop: a hundredth
  // The rear brakes' share over the slip stiffness; the axle slides outwards (negative).
  EXPECT_DOUBLE_EQ(car(kBraking).mean, 0.35 / 20.0);
  body.brake_rear_share = 0.3;
  EXPECT_DOUBLE_EQ(car(kBraking).mean, 0.3 / 20.0);
  EXPECT_NEAR(car(kSideSlip).mean, -1.0 / (9.81 * 19.0), 1e-12);
  EXPECT_NEAR(car(kSideSlip).sigma, 1.0 / (9.81 * 19.0), 1e-12);
  for (int j = 0; j < 7; ++j) EXPECT_EQ(car(j).sigma, 0.0) << "regression term " << j;
  EXPECT_EQ(car(-1).sigma, 0.0);
  EXPECT_EQ(car(TyreModel::kCoefficients).sigma, 0.0);
}

TEST(TyreCarPrior, AHeldCoefficientsSpreadCombinesTheLogsWordWithTheCars) {
  const double inf = std::numeric_limits<double>::infinity();
  const CarCoefficient at_zero{0.0, 0.02}, car{0.02, 0.02};
  // The log said nothing: the car's sigma about its own value, and its value's distance beside.
  EXPECT_DOUBLE_EQ(held_coefficient_sigma(0.3, inf, at_zero, 0.0), 0.02);
  EXPECT_DOUBLE_EQ(held_coefficient_sigma(std::nan(""), 0.01, at_zero, 0.0), 0.02);
  EXPECT_DOUBLE_EQ(held_coefficient_sigma(0.0, inf, car, 0.02), 0.02);
  EXPECT_NEAR(held_coefficient_sigma(0.0, inf, car, 0.0), std::hypot(0.02, 0.02), 1e-15);
  // Equal sigmas at zero: the combined sigma, 1/sqrt(2) of either.
  EXPECT_NEAR(held_coefficient_sigma(0.0, 0.02, at_zero, 0.0), 0.02 / std::sqrt(2.0), 1e-15);
  // Equal sigmas, the log at 0.02 and the car at zero: the mean halfway, 0.01, beside the same
  // variance; the same held at the car's value 0.02 instead, with the car at 0.02 and the log at
  // zero.
  EXPECT_NEAR(held_coefficient_sigma(0.02, 0.02, at_zero, 0.0), std::sqrt(1e-4 + 2e-4), 1e-15);
  EXPECT_NEAR(held_coefficient_sigma(0.0, 0.02, car, 0.02), std::sqrt(1e-4 + 2e-4), 1e-15);
  // Held where the log and the car agree: the combined sigma alone.
  EXPECT_NEAR(held_coefficient_sigma(0.02, 0.02, car, 0.02), 0.02 / std::sqrt(2.0), 1e-15);
  // A log far surer than the car: its own estimate and sigma about the held value.
  EXPECT_NEAR(held_coefficient_sigma(3e-4, 1e-4, {0.0, 1.0}, 0.0), std::hypot(3e-4, 1e-4), 1e-10);
  // No car's value (a regression term): the log's own estimate and sigma about the held value,
  // and nothing where the log said nothing either.
  EXPECT_NEAR(held_coefficient_sigma(0.03, 0.04, {}, 0.0), 0.05, 1e-15);
  EXPECT_NEAR(held_coefficient_sigma(0.03, 0.04, {}, 0.03), 0.04, 1e-15);
  EXPECT_EQ(held_coefficient_sigma(0.01, inf, {}, 0.0), 0.0);
  EXPECT_EQ(held_coefficient_sigma(std::nan(""), 0.01, {}, 0.0), 0.0);
}

// The mean and sigma of a Gaussian given that it is not below zero, by the midpoint rule over
// [0, mean + 12 sigma]: the independent truth for the closed form.
CarCoefficient integrated_above_zero(double mean, double sigma) {
  constexpr int kSteps = 200000;
  const double top = std::max(mean, 0.0) + 12.0 * sigma, step = top / kSteps;
  double weight = 0.0, first = 0.0, second = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double x = (i + 0.5) * step, z = (x - mean) / sigma;
    const double w = std::exp(-0.5 * z * z);
    weight += w;
    first += w * x;
    second += w * x * x;
  }
  const double m = first / weight;
  return {m, std::sqrt(second / weight - m * m)};
}

TEST(TyreCarPrior, ASlipBelowZeroIsHeldAtItsMeanAboveZero) {
  for (const double mean : {0.02, 0.0, -0.01, -0.0135, -0.03, -0.05}) {
    const CarCoefficient truth = integrated_above_zero(mean, 0.01);
    const CarCoefficient bounded = nonnegative_coefficient({mean, 0.01});
    EXPECT_NEAR(bounded.mean, truth.mean, 1e-6 * 0.01 + 1e-3 * truth.mean) << mean;
    EXPECT_NEAR(bounded.sigma, truth.sigma, 1e-3 * truth.sigma) << mean;
    EXPECT_GT(bounded.mean, 0.0) << mean;
  }
  // Far below zero, an exponential tail of rate |mean| / sigma^2: within 3 % at 9 sigma.
  const CarCoefficient far = nonnegative_coefficient({-0.09, 0.01});
  EXPECT_NEAR(far.mean, integrated_above_zero(-0.09, 0.01).mean, 0.03 * far.mean);
  EXPECT_EQ(nonnegative_coefficient({-0.01, 0.0}).mean, 0.0);
  // Held there, the spread about the held value is the bounded one's, not the Gaussian's.
  const CarCoefficient car{0.0275, 0.0275};
  const CarCoefficient combined = combined_coefficient(-0.0135, 0.006, car);
  const double held = nonnegative_coefficient(combined).mean;
  EXPECT_NEAR(held_coefficient_sigma(-0.0135, 0.006, car, held, true),
              nonnegative_coefficient(combined).sigma, 1e-12);
  EXPECT_GT(held_coefficient_sigma(-0.0135, 0.006, car, held),
            3.0 * nonnegative_coefficient(combined).sigma);
}

}  // namespace
}  // namespace odocal
