#pragma once
// Hills. The wheels roll the 3-D path, GNSS and the planar model see its horizontal projection:
// on a 6 % grade the first is 0.18 % longer, millimetres of circumference. With the grade from
// the GNSS altitude, every wheel increment is projected to the horizontal (distance x cos(pitch),
// heading change / cos(pitch), as the body turns about its tilted vertical), the forward
// accelerometer loses the gravity it feels along the slope and the gyro's rate becomes one about
// the vertical (/ cos(pitch)), so that a hilly drive calibrates like a flat one.

#include <optional>
#include <vector>

#include "odocal/data/log.hpp"

namespace odocal {

// dz/ds against the distance driven (wheel odometry, nominal circumferences).
struct GradeProfile {
  double step_m{};            // between profile points
  std::vector<double> grade;  // at 0, step, 2 step, ... metres driven
  // grade^2 less the fit's own variance: noise in the fitted grade would otherwise always
  // shorten the projection (cos of a noisy angle is biased low).
  std::vector<double> grade_squared;
  std::vector<double> grade_variance;  // of each fitted grade
  double window_m{};
  std::vector<double> wheel_distance_m;  // cumulative, per wheel sample

  double at_distance(double distance_m) const;
  double cos_pitch_at(double distance_m) const;
  // 95 % of the road's fitted |grade| is below this (a max would report the fit's noise).
  double typical_max_grade() const;
  // The 3-D distance driven over its horizontal projection, minus 1.
  double length_excess() const;
  // Variance of the projection's scale (relative) from the grade fits' noise: each window's
  // error g dg, independent between windows. Adds to the circumferences' covariance.
  double scale_variance() const;
};

// From gnss.csv's alt column by a straight-line fit of altitude against distance over window_m
// around each profile point; nothing without altitude, or too little of it.
std::optional<GradeProfile> grade_from_gnss_altitude(const Log& log, const OdometryParams& nominal,
                                                     double window_m);

// Projects the wheel increments and the gyro to the horizontal, keeps the grade beside the wheels
// (WheelStream::grade) and removes gravity along the slope from the forward accelerometer, which
// then reads the horizontal acceleration that the reference filter integrates.
void project_to_horizontal(Log& log, const GradeProfile& profile);

// Gravity along a slope of this grade (m/s^2): what the accelerometer feels on it, and the
// force per mass that climbing takes from the tyres.
double slope_gravity_mps2(double grade);

}  // namespace odocal
