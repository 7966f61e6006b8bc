#include "odocal/estimation/accelerometer_offset.hpp"

#include <algorithm>
#include <cmath>

#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/median.hpp"
#include "odocal/model/odometry_model.hpp"
#include "wheel_distance_sums.hpp"

namespace odocal {
namespace {

constexpr double kSettleS = 1.0;
// Driving straight: 2 s bins above 3 m/s turning less than 3 deg/s (the turn's -w^2 x that an
// accelerometer ahead of the rear axle reads stays below 0.004 m/s^2), the wheels' speed over 1 s
// at either end.
constexpr double kDrivingBinS = 2.0, kSpeedWindowS = 1.0;
constexpr double kMinDrivingSpeedMps = 3.0, kMaxStraightTurnRadps = 0.05;
constexpr std::size_t kMinDrivingBins = 10;
constexpr double kFullWeightS = 10.0;
// Removed where the stops show it: beyond 3 of its sigma and 0.02 m/s^2 (0.1 deg of pitch).
// Below, the sigma carries it whole, and a long log is not copied to take out what its noise
// hides (the clean 10-hour drive: 0.000 m/s^2, 343 MiB of log).
constexpr double kSignificantSigmas = 3.0, kMinRemovedOffsetMps2 = 0.02;
constexpr double kCommonSlopeSigmaMps2 = 0.005;  // 0.05 % of g, 0.03 deg

}  // namespace

std::vector<StopReading> standing_forward_readings(const ImuStream& imu,
                                                   const std::vector<Standstill>& standing) {
  std::vector<StopReading> readings;
  for (const Standstill& still : standing) {
    const double from = still.start_s + kSettleS, to = still.end_s - kSettleS;
    if (!(to > from)) continue;
    if (const std::optional<double> mean = window_sum(imu.t_s, imu.ax_mps2, from, to).mean())
      readings.push_back({*mean, to - from});
  }
  return readings;
}

std::optional<double> driving_forward_offset(const Log& log, const OdometryParams& nominal) {
  const WheelStream& wheels = log.wheels;
  if (!log.imu || wheels.size() < 3) return std::nullopt;
  const WheelDistanceSums sums(wheels, nominal);
  std::vector<double> readings;  // one allocation, however long the log
  readings.reserve(
      static_cast<std::size_t>((wheels.t_s.back() - wheels.t_s.front()) / kDrivingBinS) + 1);
  for (double from = wheels.t_s.front() + kSpeedWindowS;
       from + kDrivingBinS + kSpeedWindowS <= wheels.t_s.back(); from += kDrivingBinS) {
    const double to = from + kDrivingBinS;
    const auto v0 = sums.speed(from, kSpeedWindowS), v1 = sums.speed(to, kSpeedWindowS);
    const auto turned0 = sums.heading_at(from), turned1 = sums.heading_at(to);
    const auto broken0 = sums.breaks_at(from - kSpeedWindowS);
    const auto broken1 = sums.breaks_at(to + kSpeedWindowS);
    if (!v0 || !v1 || !turned0 || !turned1 || !broken0 || !broken1) continue;
    if (*broken1 != *broken0 || std::min(*v0, *v1) < kMinDrivingSpeedMps ||
        std::abs(*turned1 - *turned0) > kMaxStraightTurnRadps * kDrivingBinS)
      continue;
    const std::optional<double> ax = window_sum(log.imu->t_s, log.imu->ax_mps2, from, to).mean();
    if (ax) readings.push_back(*ax - (*v1 - *v0) / kDrivingBinS);
  }
  if (readings.size() < kMinDrivingBins) return std::nullopt;
  return median(std::move(readings));
}

std::optional<AccelerometerOffset> accelerometer_offset(const std::vector<StopReading>& stops) {
  if (stops.empty()) return std::nullopt;
  AccelerometerOffset offset;
  offset.stops = stops.size();
  // Each stop weighs by its settled time up to kFullWeightS: the noise's share of a longer stop
  // is small beside its slope, so that one long stop on a hill does not outvote the others.
  const auto weight = [](const StopReading& stop) {
    return std::min(stop.standing_s, kFullWeightS);
  };
  double weights = 0.0, squared_weights = 0.0;
  for (const StopReading& stop : stops) {
    offset.forward_mps2 += weight(stop) * stop.forward_mps2;
    offset.standing_s += stop.standing_s;
    weights += weight(stop);
    squared_weights += weight(stop) * weight(stop);
  }
  offset.forward_mps2 /= weights;
  const auto decide = [&] {
    offset.removed = forward_offset_stands_out(offset.forward_mps2, offset.sigma_mps2);
    return offset;
  };
  if (stops.size() < kMinStopsForOffset) {
    offset.sigma_mps2 = kUnmeasuredForwardOffsetSigmaMps2;
    return decide();
  }
  double scatter = 0.0;
  for (const StopReading& stop : stops) {
    const double off = stop.forward_mps2 - offset.forward_mps2;
    scatter += weight(stop) * off * off;
  }
  // The weighted sample variance (reliability weights) and the weighted mean's share of it.
  const double variance = scatter / (weights - squared_weights / weights);
  const double standard_error = std::sqrt(variance * squared_weights) / weights;
  offset.sigma_mps2 = std::hypot(standard_error, kCommonSlopeSigmaMps2);
  return decide();
}

bool forward_offset_stands_out(double forward_mps2, double sigma_mps2) {
  return std::abs(forward_mps2) > std::max(kSignificantSigmas * sigma_mps2, kMinRemovedOffsetMps2);
}

void remove_accelerometer_offset(ImuStream& imu, double forward_mps2) {
  for (double& ax : imu.ax_mps2) ax -= forward_mps2;
}

}  // namespace odocal
