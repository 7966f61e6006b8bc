#pragma once
// The errors a topic map's section gets when the bag does not give it its topic: said alike for
// every stream and for frames.

#include <fmt/format.h>

#include <string>

#include "odocal/error.hpp"

namespace odocal::bag {

// `names`: the bag's topics, comma-separated (empty: it has none).
[[noreturn]] inline void throw_topic_not_in_bag(const InputLocation& where,
                                                const std::string& topic,
                                                const std::string& names) {
  throw InputError(where, fmt::format("topic {} is not in the bag (it has {})", topic,
                                      names.empty() ? "none" : names));
}

// `reader`: the section reading it (wheels, frames, ...); `expected`: the types it reads.
[[noreturn]] inline void throw_topic_of_wrong_type(const InputLocation& where,
                                                   const std::string& topic,
                                                   const std::string& type,
                                                   const std::string& reader,
                                                   const std::string& expected) {
  throw InputError(where,
                   fmt::format("topic {} is {}; {} reads {}", topic, type, reader, expected));
}

}  // namespace odocal::bag
