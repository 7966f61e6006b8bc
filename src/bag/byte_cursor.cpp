#include "byte_cursor.hpp"

#include <fmt/format.h>

namespace odocal::bag {

void throw_bag_error(const ByteOrigin& origin, std::uint64_t offset, const std::string& problem) {
  const std::string where = origin.context.empty()
                                ? fmt::format("byte {}", offset)
                                : fmt::format("{}, byte {}", origin.context, offset);
  throw InputError({origin.file, 0, ""}, where + ": " + problem);
}

}  // namespace odocal::bag
