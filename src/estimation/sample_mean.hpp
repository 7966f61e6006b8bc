// A sample's mean and its standard error, for the checks that ask whether a mean error lies
// beyond a few standard errors of zero (the batch's mounting residuals, the doctor's heading
// offset).
#pragma once

#include <cmath>
#include <vector>

namespace odocal {

struct SampleMean {
  double mean{}, standard_error{};
};

// Independent values' mean and standard error; the standard error is NaN for fewer than two.
inline SampleMean sample_mean(const std::vector<double>& values) {
  const auto n = static_cast<double>(values.size());
  double mean = 0.0;
  for (const double v : values) mean += v;
  mean /= n;
  double variance = 0.0;
  for (const double v : values) variance += (v - mean) * (v - mean);
  return {mean, std::sqrt(variance / (n - 1.0) / n)};
}

}  // namespace odocal
