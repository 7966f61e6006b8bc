#pragma once
// Where a passenger car's physical tyre coefficients are (docs/tyre-model.md, "Coefficients held
// at a car's value"), for the coefficients that a log cannot identify: the batch holds them
// there, and the car's own value beside what the log said is what that holding may be off by.
// Not a prior of the free fit (nothing pulls a free coefficient towards it).

#include <algorithm>
#include <cmath>
#include <numbers>

#include "odocal/model/tyre_model.hpp"

namespace odocal {

// Where a car's tyres usually are: the radius's load sensitivity (m per N), the slip stiffness
// per unit load and the rear tyres' cornering stiffness per unit load (per rad). The rear axle's
// shares of the brake and drive forces are the body's (drive_rear_share).
inline constexpr double kCarRadiusPerNewtonM = 0.4e-6;
inline constexpr double kCarSlipStiffnessPerLoad = 20.0;
inline constexpr double kCarCorneringStiffnessPerLoad = 19.0;
// The rolling radius's centrifugal growth per (m/s)^2, which the physical terms do not model
// (docs/tyre-model.md, "Centrifugal growth"): the magic formula 6.1's example 205/60R15 tyre has
// q_V1 = 7.742e-4 at its reference speed of 16.7 m/s, and its effective rolling radius grows with
// the free radius one for one: 7.742e-4 / 16.7^2 of the free radius, times (R_0 / R_e)^3 = 1.09
// (0.3135 m free, 0.305 m rolling) for the wheel's own radius and speed. 0.19 % at 25 m/s.
inline constexpr double kCarGrowthPerSpeedSquaredS2pm2 = 3.0e-6;
// The rear axle's side slip per lateral acceleration (s^2/m) that this cornering stiffness gives:
// the axle slides outwards, so it is negative.
inline constexpr double kCarSideSlipPerLateralS2pm =
    -1.0 / (kGravityMps2 * kCarCorneringStiffnessPerLoad);
// A free-rolling axle carries none of the drive, and what its coefficient can still take up is the
// model's slop: fitted to the simulator's truth (tools/tyre_truth_regression.py; front-driven
// circuit, urban drive and Hockenheim) at most 4e-4 where its driver holds the road, 1.4e-3
// where it fishtails, so a hundredth of a driven axle's at 1 sigma.
inline constexpr double kRearDriveShareFreeRolling = 0.01;

// A car's physical coefficient: where it is expected and how far from there a car may be.
struct CarCoefficient {
  double mean = 0.0;
  double sigma = 0.0;  // zero: no car's value (a regression term)
};

// Physical coefficient j (kTyreCoefficients' order) on a car with this body (its mass and
// drivetrain) and rear circumference (m): its expected value, and a sigma of its size, so that
// a car with half or twice the usual value stays within 1 sigma. The signs are the physics':
// the radius shrinks under load, a driven or braked wheel slips, the rear axle slides outwards.
// An unstated drivetrain has no expected drive slip (zero, between a front-driven car's and a
// rear-driven one's) and a driven axle's sigma. Nothing for a regression term: their sizes are
// not a car's physics but the fit's (a skid-steer robot's are orders apart).
inline CarCoefficient car_tyre_coefficient(int j, const VehicleBody& body, double circumference_m) {
  if (j < 0 || j >= TyreModel::kCoefficients) return {};
  const double TyreModel::*member = kTyreCoefficients[static_cast<std::size_t>(j)].member;
  const auto sized = [](double mean) { return CarCoefficient{mean, std::abs(mean)}; };
  if (member == &TyreModel::k_load_s2pm) {
    const double radius_m = circumference_m / (2.0 * std::numbers::pi);
    return sized(kCarRadiusPerNewtonM * body.mass_kg / radius_m);
  }
  if (member == &TyreModel::k_drive_slip) {
    if (!body.drivetrain) return {0.0, 1.0 / kCarSlipStiffnessPerLoad};
    if (*body.drivetrain == Drivetrain::kFront)
      return {0.0, kRearDriveShareFreeRolling / kCarSlipStiffnessPerLoad};
    return sized(drive_rear_share(body) / kCarSlipStiffnessPerLoad);
  }
  if (member == &TyreModel::k_brake_slip)
    return sized(body.brake_rear_share / kCarSlipStiffnessPerLoad);
  if (member == &TyreModel::k_side_slip_s2pm) return sized(kCarSideSlipPerLateralS2pm);
  return {};
}

// What the log said of a coefficient while it was free (estimate and sigma; sigma infinite where
// it said nothing) and the car's value, as two independent Gaussian statements of one number,
// combined: where the coefficient is best held, and its sigma there.
inline CarCoefficient combined_coefficient(double free_estimate, double free_sigma,
                                           const CarCoefficient& car) {
  if (!(car.sigma > 0.0)) return {};
  if (!std::isfinite(free_sigma) || !std::isfinite(free_estimate) || !(free_sigma > 0.0))
    return car;
  const double car2 = car.sigma * car.sigma, free2 = free_sigma * free_sigma;
  return {(free_estimate * car2 + car.mean * free2) / (car2 + free2),
          std::sqrt(car2 * free2 / (car2 + free2))};
}

// A coefficient that cannot be below zero (a driven or braked axle's slip: its share of the force
// over its slip stiffness), stated as the Gaussian `combined`: its mean and sigma given that it is
// not below zero (the truncated Gaussian's), so a log that put it a little below zero holds it a
// little above, never at a value no tyre has. Beyond 8 sigma below zero the tail is exponential,
// with mean and sigma both sigma^2 / |mean|.
inline CarCoefficient nonnegative_coefficient(const CarCoefficient& combined) {
  if (!(combined.sigma > 0.0)) return {std::max(combined.mean, 0.0), 0.0};
  const double s = combined.sigma, a = -combined.mean / s;  // zero in sigmas above the mean
  if (a > 8.0) return {s / a, s / a};
  const double density = std::exp(-0.5 * a * a) / std::sqrt(2.0 * std::numbers::pi);
  const double ratio = density / (0.5 * std::erfc(a / std::numbers::sqrt2));
  return {combined.mean + s * ratio, s * std::sqrt(std::max(1.0 + a * ratio - ratio * ratio, 0.0))};
}

// The spread about `held` of a coefficient held there: the RMS of the combination above (bounded
// at zero where `nonnegative`) about the held value (the error that holding it there makes). Where
// the car has no value (a regression term) the log's statement alone, and zero where the log said
// nothing either.
inline double held_coefficient_sigma(double free_estimate, double free_sigma,
                                     const CarCoefficient& car, double held,
                                     bool nonnegative = false) {
  if (!(car.sigma > 0.0)) {
    if (!std::isfinite(free_sigma) || !std::isfinite(free_estimate) || !(free_sigma > 0.0))
      return 0.0;
    return std::hypot(free_estimate - held, free_sigma);
  }
  CarCoefficient combined = combined_coefficient(free_estimate, free_sigma, car);
  if (nonnegative) combined = nonnegative_coefficient(combined);
  return std::hypot(combined.mean - held, combined.sigma);
}

}  // namespace odocal
