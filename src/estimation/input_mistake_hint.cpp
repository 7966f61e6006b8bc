#include "input_mistake_hint.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace odocal {
namespace {

struct KnownFactor {
  double factor;
  const char* cause;  // why the circumference would come out `factor` times too large
};

// Mistakes that make the wheel distance (or the GNSS distance it is compared with) wrong by a
// fixed factor; the estimate then lands that factor away from the truth.
constexpr std::array<KnownFactor, 8> kKnownFactors{{
    {2.0 * std::numbers::pi, "wheel angles in radians read as revolutions (or the reverse)"},
    {60.0, "wheel speeds in rpm read as revolutions per second (or the reverse)"},
    {3.6, "a speed in km/h read as m/s (or the reverse)"},
    {std::numbers::pi, "a wheel diameter given where the circumference belongs (or the reverse)"},
    {2.0, "a wheel diameter given where the radius belongs (or the reverse)"},
    {1000.0, "a time column in ms read as s (or the reverse), or mm read as m"},
    {10.0, "a time stamp scale off by 10"},
    {180.0 / std::numbers::pi, "wheel angles in degrees read as radians (or the reverse)"},
}};

bool near(double ratio, double factor) { return std::abs(std::log(ratio / factor)) < 0.03; }

}  // namespace

std::string likely_input_mistake(double ratio, const Log& log) {
  if (!(ratio > 0.0) || !std::isfinite(ratio)) {
    return "the wheel signs look reversed, the GNSS time stamps are off (scale or clock "
           "offset), or a stream is far outside its physical range (check wheels.csv's sign "
           "convention, the time columns and the units of every column)";
  }
  const double larger = std::max(ratio, 1.0 / ratio);
  std::vector<std::string> causes;
  const double whole = std::round(larger);
  if (log.wheels.unit_rear == WheelUnit::kTicks && log.vehicle.ticks_per_rev && whole >= 2.0 &&
      near(larger, whole)) {
    const double configured = *log.vehicle.ticks_per_rev;
    causes.push_back(
        fmt::format("ticks_per_rev off by a factor of {:.0f} (vehicle.yaml says {}; "
                    "try {})",
                    whole, configured, ratio > 1.0 ? configured / whole : configured * whole));
  }
  for (const KnownFactor& known : kKnownFactors)
    if (near(larger, known.factor)) causes.emplace_back(known.cause);
  if (causes.empty()) {
    return fmt::format(
        "{:.4g} times the nominal value: likely a unit or scale in the wheel or GNSS columns, a "
        "time scale, a clock offset between the streams, or a wrong nominal circumference in "
        "vehicle.yaml",
        ratio);
  }
  return fmt::format("{:.4g} times {} than nominal: likely {}", larger,
                     ratio > 1.0 ? "larger" : "smaller", fmt::join(causes, ", or "));
}

}  // namespace odocal
