#pragma once
// Command-line numbers: finite and inside what they can physically be. CLI11's own checks let
// "nan" through (every comparison with NaN is false).

#include <CLI/CLI.hpp>

#include "odocal/data/physical_limits.hpp"

namespace odocal::cli {

// A finite number from min to max.
CLI::Validator finite_in(double min, double max);
inline CLI::Validator finite_in(PhysicalRange range) { return finite_in(range.min, range.max); }

}  // namespace odocal::cli
