#include "odocal/estimation/rolled_distance.hpp"

#include <cmath>

namespace odocal {

std::vector<double> rolled_distance_m(const WheelStream& wheels, const OdometryParams& params) {
  std::vector<double> rolled(wheels.size(), 0.0);
  for (std::size_t k = 1; k < wheels.size(); ++k)
    rolled[k] = rolled[k - 1] + std::abs(body_increment(wheels.increment(k), params).distance_m);
  return rolled;
}

}  // namespace odocal
