#include "units.hpp"

#include <array>
#include <numbers>

namespace odocal::detail {
namespace {

struct NamedUnit {
  const char* name;
  Unit unit;
};

constexpr double kPi = std::numbers::pi;
constexpr std::array<NamedUnit, 22> kUnits = {{
    {"s", {Quantity::kTime, 1.0}},
    {"ms", {Quantity::kTime, 1e-3}},
    {"us", {Quantity::kTime, 1e-6}},
    {"ns", {Quantity::kTime, 1e-9}},
    {"m", {Quantity::kLength, 1.0}},
    {"km", {Quantity::kLength, 1e3}},
    {"m/s", {Quantity::kSpeed, 1.0}},
    {"km/h", {Quantity::kSpeed, 1.0 / 3.6}},
    {"mph", {Quantity::kSpeed, 0.44704}},
    {"rad", {Quantity::kAngle, 1.0}},
    {"deg", {Quantity::kAngle, kPi / 180.0}},
    {"rev", {Quantity::kAngle, 2.0 * kPi}},
    {"rad/s", {Quantity::kAngularSpeed, 1.0}},
    {"deg/s", {Quantity::kAngularSpeed, kPi / 180.0}},
    {"rpm", {Quantity::kAngularSpeed, 2.0 * kPi / 60.0}},
    {"m/s^2", {Quantity::kAcceleration, 1.0}},
    {"g", {Quantity::kAcceleration, 9.80665}},
    {"ticks", {Quantity::kTicks, 1.0}},
    {"N", {Quantity::kForce, 1.0}},
    {"daN", {Quantity::kForce, 10.0}},
    {"kN", {Quantity::kForce, 1e3}},
    {"lbf", {Quantity::kForce, 4.4482216152605}},
}};

}  // namespace

std::optional<Unit> parse_unit(const std::string& name) {
  for (const NamedUnit& named : kUnits) {
    if (name == named.name) return named.unit;
  }
  return std::nullopt;
}

std::string unit_names(Quantity quantity) {
  std::string names;
  for (const NamedUnit& named : kUnits) {
    if (named.unit.quantity != quantity) continue;
    if (!names.empty()) names += ", ";
    names += named.name;
  }
  return names;
}

}  // namespace odocal::detail
