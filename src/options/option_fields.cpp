#include "odocal/options/option_fields.hpp"

#include <fmt/format.h>

#include <cstdlib>

namespace odocal {

std::string format_option_number(double value) {
  // Of the shortest round-trip text ("60", "1000000000000") and the one with the fewest
  // significant digits in %g form ("1e+12"), the shorter; both read back as the same double.
  std::string shortest = fmt::format("{}", value);
  for (int digits = 1; digits < 17; ++digits) {
    std::string text = fmt::format("{:.{}g}", value, digits);
    if (std::strtod(text.c_str(), nullptr) == value)
      return text.size() < shortest.size() ? text : shortest;
  }
  return shortest;
}

}  // namespace odocal
