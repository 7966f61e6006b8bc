#pragma once
// What a wheel-odometry vehicle can physically be, from a small robot to a truck. Readers and the
// command line refuse values outside (exit 2), so that no computation starts from a track width
// of a nanometre or a circumference of a kilometre.

namespace odocal {

struct PhysicalRange {
  double min;
  double max;
  bool contains(double value) const { return value >= min && value <= max; }  // false for NaN
};

inline constexpr PhysicalRange kTrackWidthM{0.05, 5.0};
inline constexpr PhysicalRange kWheelbaseM{0.05, 20.0};
inline constexpr PhysicalRange kCircumferenceM{0.05, 10.0};  // wheel radius 8 mm to 1.6 m
inline constexpr PhysicalRange kTyrePressure{0.3, 1.5};      // relative to the nominal inflation
inline constexpr PhysicalRange kTyreWearMm{-50.0, 50.0};     // radius lost (negative: grown)
// Tyre model coefficients: odocal/model/tyre_model.hpp's kTyreCoefficients has their bounds.
// The vehicle's body (tyre_model.hpp's VehicleBody): any road vehicle.
inline constexpr PhysicalRange kAxleLoadShare{0.05, 0.95};
inline constexpr PhysicalRange kCgHeightM{0.05, 5.0};
inline constexpr PhysicalRange kRollShare{0.0, 1.0};
inline constexpr PhysicalRange kVehicleMassKg{1.0, 1e5};
inline constexpr PhysicalRange kDragAreaM2{0.0, 50.0};
inline constexpr PhysicalRange kRollingResistance{0.0, 0.2};
inline constexpr PhysicalRange kTyreFriction{0.1, 2.0};
inline constexpr PhysicalRange kSlipCurveShape{1.0, 2.0};
// A tyre's cornering stiffness per unit load, 1/rad: a road tyre's 8-30, a racing slick's more.
inline constexpr PhysicalRange kCorneringStiffnessPerLoad{3.0, 60.0};
inline constexpr PhysicalRange kAxleForceShare{0.0, 1.0};
// Where a sensor is mounted from the rear axle's centre: anywhere on a vehicle up to a truck's.
inline constexpr PhysicalRange kMountingOffsetM{-20.0, 20.0};

// Log streams. Times are seconds on any clock up to 300 years from its zero (Unix time fits);
// positions are local metres (UTM northings fit); accelerations reach 50 g and rates 50 rad/s
// (a crash, a spinning robot); headings may be unwrapped over a long drive.
inline constexpr PhysicalRange kTimeS{-1e10, 1e10};
inline constexpr PhysicalRange kPositionM{-1e8, 1e8};
inline constexpr PhysicalRange kAltitudeM{-1e4, 1e5};
inline constexpr PhysicalRange kAccelerationMps2{-500.0, 500.0};
inline constexpr PhysicalRange kRateRadps{-50.0, 50.0};
inline constexpr PhysicalRange kHeadingRad{-1e4, 1e4};

}  // namespace odocal
