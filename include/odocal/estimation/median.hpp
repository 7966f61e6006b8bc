#pragma once
// The median of a sample (the upper middle value for an even count), NaN for none; and a normal
// sample's sigma from it, robust to outliers.

#include <algorithm>
#include <cmath>
#include <vector>

namespace odocal {

// Single or double precision: a long log's values for a median may be kept as floats.
template <class Real>
double median(std::vector<Real> values) {
  if (values.empty()) return NAN;
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return static_cast<double>(*middle);
}

// Sigma of a zero-mean normal sample from its absolute values: |N(0, 1)|'s median is 1 / 1.4826.
// Zero for none.
template <class Real>
double normal_sigma_from_absolute(std::vector<Real> absolute_values) {
  constexpr double kMedianAbsoluteToSigma = 1.4826;
  if (absolute_values.empty()) return 0.0;
  return kMedianAbsoluteToSigma * median(std::move(absolute_values));
}

}  // namespace odocal
