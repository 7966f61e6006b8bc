#pragma once
// How large a passenger car's physical tyre coefficients are (docs/tyre-model.md, "The physical
// terms"), for the coefficients that a log cannot identify: the batch holds them at zero, and
// the car's own value is the error that holding makes. Not a prior of the fit (nothing pulls a
// free coefficient towards it): only what a held one is taken to be uncertain by.

#include <cmath>
#include <limits>
#include <numbers>

#include "odocal/model/tyre_model.hpp"

namespace odocal {

// Where a car's tyres usually are: the radius's load sensitivity (m per N), the slip stiffness
// per unit load, the rear axle's share of the braking force, and the rear tyres' cornering
// stiffness per unit load (per rad).
inline constexpr double kCarRadiusPerNewtonM = 0.4e-6;
inline constexpr double kCarSlipStiffnessPerLoad = 20.0;
inline constexpr double kCarRearBrakeShare = 0.35;
inline constexpr double kCarCorneringStiffnessPerLoad = 19.0;
// The share of the drive force on the rear axle: all of it, or an all-wheel drive's typical
// 0.5; a free-rolling axle carries none, and what its coefficient can still take up is the
// model's slop (the simulator's front-driven circuit fits -0.0009 and -0.0019 at sigma 0.0015),
// taken as a twentieth of a driven axle's.
inline constexpr double kRearDriveShareAll = 0.5;
inline constexpr double kRearDriveShareFreeRolling = 0.05;

// 1 sigma about zero of physical coefficient j (kTyreCoefficients' order) on a car with this
// body (its mass and drivetrain) and rear circumference (m): its expected size, so that a car
// with half or twice the usual value stays within 1 sigma of it. Zero for a regression term: their
// sizes are not a car's physics but the fit's (a skid-steer robot's are orders apart).
inline double car_tyre_coefficient_sigma(int j, const VehicleBody& body, double circumference_m) {
  constexpr double kGravity = 9.81;
  if (j < 0 || j >= TyreModel::kCoefficients) return 0.0;
  const double TyreModel::*member = kTyreCoefficients[static_cast<std::size_t>(j)].member;
  if (member == &TyreModel::k_load_s2pm) {
    const double radius_m = circumference_m / (2.0 * std::numbers::pi);
    return kCarRadiusPerNewtonM * body.mass_kg / radius_m;
  }
  if (member == &TyreModel::k_drive_slip) {
    // Unstated: a driven axle's, which covers every car.
    const double share = body.drivetrain == Drivetrain::kFront ? kRearDriveShareFreeRolling
                         : body.drivetrain == Drivetrain::kAll ? kRearDriveShareAll
                                                               : 1.0;
    return share / kCarSlipStiffnessPerLoad;
  }
  if (member == &TyreModel::k_brake_slip) return kCarRearBrakeShare / kCarSlipStiffnessPerLoad;
  if (member == &TyreModel::k_side_slip_s2pm)
    return 1.0 / (kGravity * kCarCorneringStiffnessPerLoad);
  return 0.0;
}

// The spread about zero of a coefficient held at zero: what the log said of it while it was
// free (estimate and sigma, sigma infinite where it said nothing) combined with the car's
// spread, as two independent Gaussian statements of one number; the RMS of the combination
// about zero (the error that holding it at zero makes). Zero where the car's spread is zero.
inline double held_coefficient_sigma(double free_estimate, double free_sigma, double car_sigma) {
  if (!(car_sigma > 0.0)) return 0.0;
  if (!std::isfinite(free_sigma) || !std::isfinite(free_estimate) || !(free_sigma > 0.0))
    return car_sigma;
  const double car2 = car_sigma * car_sigma, free2 = free_sigma * free_sigma;
  const double mean = free_estimate * car2 / (car2 + free2);
  const double variance = car2 * free2 / (car2 + free2);
  return std::sqrt(mean * mean + variance);
}

}  // namespace odocal
