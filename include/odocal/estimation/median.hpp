#pragma once
// The median of a sample (the upper middle value for an even count), NaN for none.

#include <algorithm>
#include <cmath>
#include <vector>

namespace odocal {

inline double median(std::vector<double> values) {
  if (values.empty()) return NAN;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace odocal
