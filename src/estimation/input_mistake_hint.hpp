#pragma once
// Words for an estimate far from the nominal circumference: which input mistake the ratio points
// to, so that the user knows what to fix.

#include <string>

#include "odocal/data/log.hpp"

namespace odocal {

// `ratio` = estimated / nominal circumference (the mean over both rear wheels).
std::string likely_input_mistake(double ratio, const Log& log);

}  // namespace odocal
