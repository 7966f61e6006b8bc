#include "number_checks.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string>

namespace odocal::cli {

CLI::Validator finite_in(double min, double max) {
  return CLI::Validator(
      [min, max](std::string& text) -> std::string {
        double value = 0.0;
        try {
          std::size_t used = 0;
          value = std::stod(text, &used);
          if (used != text.size()) return fmt::format("'{}' is not a number", text);
        } catch (const std::exception&) {
          return fmt::format("'{}' is not a number", text);
        }
        if (!std::isfinite(value) || value < min || value > max)
          return fmt::format("{} is outside {} to {}", text, min, max);
        return "";
      },
      fmt::format("NUMBER in [{}, {}]", min, max));
}

}  // namespace odocal::cli
