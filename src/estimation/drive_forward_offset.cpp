#include "odocal/estimation/drive_forward_offset.hpp"

#include <algorithm>
#include <vector>

#include "odocal/estimation/accelerometer_offset.hpp"
#include "odocal/estimation/accelerometer_walk.hpp"
#include "odocal/estimation/median.hpp"
#include "odocal/model/gravity.hpp"
#include "odocal/model/tyre_car_prior.hpp"
#include "wheel_distance_sums.hpp"

namespace odocal {
namespace {

// An IMU stretch ends at a gap longer than this (a 10 Hz accelerometer's period with margin).
constexpr double kMaxImuGapS = 0.25;
constexpr double kMinStretchS = 5.0, kSpeedWindowS = 1.0;
constexpr double kMinDurationS = 30.0, kMinDistanceM = 200.0;
// What the drive's terms are known to (the header's list).
constexpr double kPlaceSigmaM = 0.5, kYawSigmaRad = 0.01745;
constexpr double kAltitudeSigmaM = 3.0, kClosedLoopSlopeSigmaMps2 = 0.03;
// A drive that ends within this of where it began climbed nothing net; each end's place is the
// median of this many fixes.
constexpr double kClosedLoopGapM = 50.0;
constexpr std::size_t kPlaceFixes = 10;

}  // namespace

void DriveForwardSums::add(const DriveForwardSums& other) {
  duration_s += other.duration_s;
  squared_steps_s2 += other.squared_steps_s2;
  forward_less_gain += other.forward_less_gain;
  lateral += other.lateral;
  lateral_squared += other.lateral_squared;
  turn_squared += other.turn_squared;
  distance_m += other.distance_m;
  accelerometer_noise_mps2 = std::max(accelerometer_noise_mps2, other.accelerometer_noise_mps2);
}

DriveForwardSums drive_forward_sums(const Log& log, const OdometryParams& nominal, double from_s,
                                    double to_s) {
  DriveForwardSums sums;
  const WheelStream& wheels = log.wheels;
  if (!log.imu || wheels.size() < 3) return sums;
  const ImuStream& imu = *log.imu;
  const WheelDistanceSums wheel_sums(wheels, nominal);
  // Within the wheels' span, so that a stretch's ends have their speed.
  from_s = std::max(from_s, wheels.t_s.front() + 0.5 * kSpeedWindowS);
  to_s = std::min(to_s, wheels.t_s.back() - 0.5 * kSpeedWindowS);
  if (!(to_s > from_s)) return sums;
  const auto first = std::lower_bound(imu.t_s.begin(), imu.t_s.end(), from_s) - imu.t_s.begin();
  const auto last = std::lower_bound(imu.t_s.begin(), imu.t_s.end(), to_s) - imu.t_s.begin();
  const auto begin = static_cast<std::size_t>(first), end = static_cast<std::size_t>(last);
  const auto speed_at = [&](std::size_t k) { return wheel_sums.speed(imu.t_s[k], kSpeedWindowS); };
  // One stretch [start, stop]: its trapezoid integrals between the samples nearest its ends
  // that have a speed. Moved in, not dropped: a chain break beside an end, or a speed window
  // one rounding short of the wheels' first sample, would otherwise lose a whole drive.
  const auto add_stretch = [&](std::size_t start, std::size_t stop) {
    while (start < stop && !speed_at(start)) ++start;
    while (stop > start && !speed_at(stop)) --stop;
    const double t0 = imu.t_s[start], t1 = imu.t_s[stop];
    if (t1 - t0 < kMinStretchS) return;
    const auto v0 = speed_at(start), v1 = speed_at(stop);
    if (!v0 || !v1) return;
    DriveForwardSums stretch;
    for (std::size_t k = start; k < stop; ++k) {
      const double dt = imu.t_s[k + 1] - imu.t_s[k];
      const auto trapezoid = [&](double a, double b) { return 0.5 * (a + b) * dt; };
      const double ay0 = imu.ay_mps2[k], ay1 = imu.ay_mps2[k + 1];
      const double wz0 = imu.wz_radps[k], wz1 = imu.wz_radps[k + 1];
      stretch.duration_s += dt;
      stretch.squared_steps_s2 += dt * dt;
      stretch.forward_less_gain += trapezoid(imu.ax_mps2[k], imu.ax_mps2[k + 1]);
      stretch.lateral += trapezoid(ay0, ay1);
      stretch.lateral_squared += trapezoid(ay0 * ay0, ay1 * ay1);
      stretch.turn_squared += trapezoid(wz0 * wz0, wz1 * wz1);
    }
    stretch.forward_less_gain -= *v1 - *v0;
    const auto d0 = wheel_sums.distance_at(t0), d1 = wheel_sums.distance_at(t1);
    if (d0 && d1) stretch.distance_m = std::abs(*d1 - *d0);
    sums.add(stretch);
  };
  if (end <= begin + 1) return sums;
  std::size_t start = begin;
  for (std::size_t k = begin + 1; k < end; ++k) {
    if (imu.t_s[k] - imu.t_s[k - 1] > kMaxImuGapS) {
      add_stretch(start, k - 1);
      start = k;
    }
  }
  add_stretch(start, end - 1);
  if (sums.duration_s > 0.0) {
    sums.accelerometer_noise_mps2 = white_noise_sigma(
        std::vector<double>(imu.ax_mps2.begin() + first, imu.ax_mps2.begin() + last));
  }
  return sums;
}

std::optional<DriveForwardOffset> drive_forward_offset(const DriveForwardSums& sums,
                                                       const VehicleBody& body,
                                                       std::optional<DriveSlope> slope) {
  if (!slope || sums.duration_s < kMinDurationS || sums.distance_m < kMinDistanceM)
    return std::nullopt;
  const double T = sums.duration_s;
  // ax = dv/dt - w (vy_rear + w b) + offset, with vy_rear = k ay v and v w = ay, b the IMU's
  // place ahead of the rear axle.
  const double b = accelerometer_position_m(body).x();
  // A car's rear side slip, known to its own size (tyre_car_prior.hpp).
  const double side_slip = kCarSideSlipPerLateralS2pm;
  const double turn_squared = sums.turn_squared / T, lateral_squared = sums.lateral_squared / T;
  DriveForwardOffset offset;
  offset.duration_s = T;
  offset.distance_m = sums.distance_m;
  offset.forward_mps2 = sums.forward_less_gain / T + side_slip * lateral_squared + b * turn_squared;
  const double noise = sums.accelerometer_noise_mps2 * std::sqrt(sums.squared_steps_s2) / T;
  const double slope_sigma = *slope == DriveSlope::kProjected
                                 ? kGravityMps2 * std::sqrt(2.0) * kAltitudeSigmaM / sums.distance_m
                                 : kClosedLoopSlopeSigmaMps2;
  offset.sigma_mps2 =
      std::sqrt(noise * noise + std::pow(side_slip * lateral_squared, 2) +
                std::pow(kPlaceSigmaM * turn_squared, 2) +
                std::pow(kYawSigmaRad * sums.lateral / T, 2) + slope_sigma * slope_sigma);
  offset.removed = forward_offset_stands_out(offset.forward_mps2, offset.sigma_mps2);
  return offset;
}

void DriveForwardMeasure::add(const Log& context, double from_s, double to_s, bool projected) {
  sums_.add(drive_forward_sums(context, nominal_, from_s, to_s));
  all_projected_ = all_projected_ && projected;
  any_projected_ = any_projected_ || projected;
  const GnssStream& gnss = context.gnss;
  const auto begin = static_cast<std::size_t>(
      std::lower_bound(gnss.t_s.begin(), gnss.t_s.end(), from_s) - gnss.t_s.begin());
  const auto end = static_cast<std::size_t>(
      std::lower_bound(gnss.t_s.begin() + static_cast<std::ptrdiff_t>(begin), gnss.t_s.end(),
                       to_s) -
      gnss.t_s.begin());
  const auto place = [&](std::size_t from, std::size_t to) {
    const auto column = [&](const std::vector<double>& values) {
      return median(std::vector<double>(values.begin() + static_cast<std::ptrdiff_t>(from),
                                        values.begin() + static_cast<std::ptrdiff_t>(to)));
    };
    return std::make_pair(column(gnss.x_m), column(gnss.y_m));
  };
  if (end > begin) {
    if (!start_xy_) start_xy_ = place(begin, std::min(end, begin + kPlaceFixes));
    end_xy_ = place(end - std::min(end - begin, kPlaceFixes), end);
  }
}

std::optional<DriveForwardOffset> DriveForwardMeasure::measure() const {
  std::optional<DriveSlope> slope;
  if (all_projected_) {
    slope = DriveSlope::kProjected;
  } else if (!any_projected_ && start_xy_ && end_xy_ &&
             std::hypot(end_xy_->first - start_xy_->first, end_xy_->second - start_xy_->second) <=
                 kClosedLoopGapM) {
    slope = DriveSlope::kClosedLoop;
  }
  return drive_forward_offset(sums_, body_, slope);
}

}  // namespace odocal
