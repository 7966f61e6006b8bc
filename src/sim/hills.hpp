#pragma once
// The road's profile on hills (Terrain in scenario.hpp): z(s) = A sin(k s) over the horizontal
// distance s driven, k rounded so that every lap closes. The graded motion (what the sensors see)
// and the vehicle dynamics (the drive force that climbing takes) read the same road.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "odocal/sim/scenario.hpp"

namespace odocal::sim {

// The body's pitch on a road of grade dz/ds (positive uphill).
struct Pitch {
  double sin{0.0}, cos{1.0};
  Pitch() = default;
  explicit Pitch(double grade)
      : sin(grade / std::sqrt(1.0 + grade * grade)), cos(1.0 / std::sqrt(1.0 + grade * grade)) {}
};

class Hills {
 public:
  Hills(const Terrain& terrain, double lap_length_m) {
    const double waves = std::max(1.0, std::round(lap_length_m / terrain.wavelength_m));
    wavenumber_1pm_ = 2.0 * std::numbers::pi * waves / lap_length_m;
    amplitude_m_ = terrain.max_grade / wavenumber_1pm_;
  }

  double altitude_m(double s_m) const { return amplitude_m_ * std::sin(wavenumber_1pm_ * s_m); }
  double grade(double s_m) const {  // dz/ds
    return amplitude_m_ * wavenumber_1pm_ * std::cos(wavenumber_1pm_ * s_m);
  }

 private:
  double amplitude_m_{};
  double wavenumber_1pm_{};
};

}  // namespace odocal::sim
