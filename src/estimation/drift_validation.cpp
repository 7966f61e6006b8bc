#include "odocal/estimation/drift_validation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>

#include "gaussian_radius.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/wheel_gaps.hpp"
#include "odocal/model/odometry_model.hpp"

namespace odocal {
namespace {

// Linear-interpolated percentile (p in [0, 1]) of unsorted values.
double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  const double position = p * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(position));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  return values[below] + (position - static_cast<double>(below)) * (values[above] - values[below]);
}

DriftStatistics statistics(const std::vector<WindowDrift>& windows) {
  std::vector<double> errors, percents;
  for (const WindowDrift& w : windows) {
    errors.push_back(w.end_error_m);
    percents.push_back(w.drift_percent);
  }
  return {windows.size(), percentile(errors, 0.5), percentile(errors, 0.95),
          percentile(percents, 0.5), percentile(percents, 0.95)};
}

// Whether the wheel stream has a gap (wheel_gaps.hpp) between reference samples first and last.
bool spans_gap(const WheelStream& wheels, const ReferenceTrajectory& reference, std::size_t first,
               std::size_t last, double max_gap_s) {
  for (std::size_t i = first + 1; i <= last; ++i) {
    const std::size_t k = reference.first_wheel_index + i;
    if (wheels.t_s[k] - wheels.t_s[k - 1] > max_gap_s || wheels.breaks_at(k)) return true;
  }
  return false;
}

// Dead reckoning over reference samples [first, last] from the reference pose at `first`.
WindowDrift window_drift(const WheelStream& wheels, const ReferenceTrajectory& reference,
                         std::size_t first, std::size_t last, const OdometryParams& params) {
  Pose2 pose = reference.poses[first];
  double distance = 0.0;
  for (std::size_t i = first + 1; i <= last; ++i) {
    const std::size_t k = reference.first_wheel_index + i;
    const Pose2 next = predict_pose(pose, wheels.increment(k), params, wheels.side_slip(k));
    distance += (next.head<2>() - pose.head<2>()).norm();
    pose = next;
  }
  const double error = (pose.head<2>() - reference.poses[last].head<2>()).norm();
  return {reference.times(wheels)[first], distance, error, 100.0 * error / distance};
}

// Covariance of the end error the reference's own uncertainty makes over [first, last]
// (ReferenceUncertainty): d(R(yaw) D)/d(yaw) = D turned by 90 degrees.
Eigen::Matrix2d reference_end_covariance(const ReferenceTrajectory& reference, std::size_t first,
                                         std::size_t last) {
  const Eigen::Vector2d displacement =
      reference.poses[last].head<2>() - reference.poses[first].head<2>();
  Eigen::Matrix<double, 2, 3> start;
  start << Eigen::Matrix2d::Identity(), Eigen::Vector2d(-displacement.y(), displacement.x());
  return start * reference.covariance[first] * start.transpose() +
         reference.covariance[last].topLeftCorner<2, 2>();
}

ReferenceUncertainty reference_uncertainty(const std::vector<Eigen::Matrix2d>& covariances,
                                           const std::vector<WindowDrift>& windows) {
  ReferenceUncertainty u;
  std::vector<double> hundredths;  // a percent of each window's distance, in metres
  for (std::size_t i = 0; i < windows.size(); ++i) {
    u.rms_m.push_back(std::sqrt(covariances[i].trace()));
    hundredths.push_back(windows[i].distance_m / 100.0);
  }
  u.median_end_error_m =
      gaussian_radius_median(covariances, std::vector<double>(covariances.size(), 1.0));
  u.median_drift_percent = gaussian_radius_median(covariances, hundredths);
  return u;
}

}  // namespace

std::string DriftValidationOptions::validate() const {
  if (!(window_s > 0.0)) return "window_s must be positive";
  if (!(step_s >= 0.0)) return "step_s must not be negative";
  if (min_window_distance_m < 0.0) return "min_window_distance_m must not be negative";
  if (!(tick_smoothing_s >= 0.0)) return "tick_smoothing_s must not be negative";
  return "";
}

DriftValidation validate_drift(const WheelStream& wheels, const ReferenceTrajectory& reference,
                               const OdometryParams& nominal, const OdometryParams& calibrated,
                               const DriftValidationOptions& options) {
  return validate_drift(wheels, wheels, reference, nominal, calibrated, options);
}

DriftValidation validate_drift(const WheelStream& counted_wheels,
                               const WheelStream& counted_calibrated_wheels,
                               const ReferenceTrajectory& reference, const OdometryParams& nominal,
                               const OdometryParams& calibrated,
                               const DriftValidationOptions& options) {
  if (counted_calibrated_wheels.size() != counted_wheels.size())
    throw Error("validate_drift: both wheel streams must hold the same samples");
  // The reference's times are the wheels' (reference_filter.hpp): it must be these wheels'.
  if (reference.first_wheel_index + reference.poses.size() > counted_wheels.size())
    throw Error("validate_drift: the reference reaches past the wheel stream it was computed on");
  if (const std::string problem = options.validate(); !problem.empty())
    throw Error("invalid validation options: " + problem);
  const bool with_uncertainty = !reference.covariance.empty();
  if (with_uncertainty && reference.covariance.size() != reference.poses.size())
    throw Error("validate_drift: the reference's covariance must hold one matrix per pose");
  const WheelStream wheels = dequantised_ticks(counted_wheels, options.tick_smoothing_s);
  const WheelStream calibrated_wheels =
      dequantised_ticks(counted_calibrated_wheels, options.tick_smoothing_s);
  DriftValidation result;
  std::vector<Eigen::Matrix2d> reference_end;
  const double max_gap_s = default_max_wheel_gap_s(wheels);
  const std::span<const double> t = reference.times(wheels);
  // Disjoint windows share their end and start sample; overlapping ones start step_s apart.
  const auto next_start = [&](std::size_t first, std::size_t last) {
    if (options.step_s <= 0.0) return last;
    std::size_t next = first + 1;
    while (next + 1 < t.size() && t[next] - t[first] < options.step_s) ++next;
    return next;
  };
  std::size_t first = 0;
  while (first + 1 < t.size()) {
    std::size_t last = first;
    while (last + 1 < t.size() && t[last + 1] - t[first] <= options.window_s) ++last;
    if (t[last] - t[first] < 0.99 * options.window_s) break;     // the short tail
    if (spans_gap(wheels, reference, first, last, max_gap_s)) {  // unknown motion inside
      ++result.windows_with_gaps;
      first = next_start(first, last);
      continue;
    }
    const WindowDrift with_nominal = window_drift(wheels, reference, first, last, nominal);
    // A window without driving has no drift to give in % of its distance, whatever the minimum.
    if (with_nominal.distance_m >= options.min_window_distance_m && with_nominal.distance_m > 0.0) {
      result.nominal.push_back(with_nominal);
      result.calibrated.push_back(
          window_drift(calibrated_wheels, reference, first, last, calibrated));
      if (with_uncertainty)
        reference_end.push_back(reference_end_covariance(reference, first, last));
    }
    first = next_start(first, last);
  }
  if (result.nominal.empty()) {
    throw InsufficientDataError(
        fmt::format("no {} s window with at least {} m of driving: nothing to validate",
                    options.window_s, options.min_window_distance_m));
  }
  result.nominal_statistics = statistics(result.nominal);
  result.calibrated_statistics = statistics(result.calibrated);
  if (with_uncertainty) result.reference = reference_uncertainty(reference_end, result.nominal);
  return result;
}

bool adopt_found_antenna(VehicleConfig& vehicle, const std::optional<Eigen::Vector2d>& found_m) {
  if (!found_m || vehicle.gnss_position_m) return false;
  vehicle.gnss_position_m = found_m;
  return true;
}

}  // namespace odocal
