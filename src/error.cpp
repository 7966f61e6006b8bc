#include "odocal/error.hpp"

#include <fmt/format.h>

namespace odocal {
namespace {

std::string format_input_error(const InputLocation& location, const std::string& problem) {
  return fmt::format("{}{}: {}{}", location.file.empty() ? std::string("input") : location.file,
                     location.line > 0 ? fmt::format(":{}", location.line) : std::string(),
                     location.field.empty() ? std::string() : fmt::format("'{}': ", location.field),
                     problem);
}

}  // namespace

InputError::InputError(InputLocation location, const std::string& problem)
    : Error(format_input_error(location, problem)),
      location_(std::move(location)),
      problem_(problem) {}

}  // namespace odocal
