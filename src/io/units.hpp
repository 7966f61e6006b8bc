#pragma once
// Units the CSV importer understands, and their conversion to odocal's SI units.

#include <optional>
#include <string>

namespace odocal::detail {

enum class Quantity {
  kTime,
  kLength,
  kSpeed,
  kAngle,
  kAngularSpeed,
  kAcceleration,
  kTicks,
  kForce
};

struct Unit {
  Quantity quantity;
  double to_si;  // multiply a value by this to get s, m, m/s, rad, rad/s, m/s^2, ticks or N
};

// "s", "ms", "us", "ns", "m", "km", "m/s", "km/h", "mph", "rad", "deg", "rev", "rad/s", "deg/s",
// "rpm", "m/s^2", "g", "ticks", "N", "daN", "kN", "lbf". nullopt for anything else.
std::optional<Unit> parse_unit(const std::string& name);

// The list of accepted names for a quantity, for messages.
std::string unit_names(Quantity quantity);

}  // namespace odocal::detail
