#include "mounting_detection.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "latency_detection.hpp"
#include "odocal/model/angle.hpp"
#include "second_fit.hpp"

namespace odocal::batch {

namespace {

bool shows(double mean, double standard_error, double min_size) {
  return std::abs(mean) >= min_size &&
         std::abs(mean) >= BatchOptions::kMountingSigmas * standard_error;
}

}  // namespace

MountingFound mounting_found(const BatchSummary& with, const MountingSignature& shown,
                             const BatchOptions& stated) {
  MountingFound found;
  if (shown.lever_arm) {
    const EstimatedParameter* x = estimated_parameter(with, "lever_arm_x_m");
    const EstimatedParameter* y = estimated_parameter(with, "lever_arm_y_m");
    found.complete = found.complete && x && y;
    if (x && y) {
      found.lever_arm_m = {x->value, y->value};
      found.lever_arm_sigma_m = {x->sigma, y->sigma};
      const double dx = x->value - stated.lever_arm_x_m, dy = y->value - stated.lever_arm_y_m;
      found.significant =
          found.significant || (std::hypot(dx, dy) >= kMinLeverArmM &&
                                (std::abs(dx) > BatchOptions::kMountingSigmas * x->sigma ||
                                 std::abs(dy) > BatchOptions::kMountingSigmas * y->sigma));
    }
  }
  if (shown.heading_bias) {
    const EstimatedParameter* bias = estimated_parameter(with, "heading_bias_rad");
    found.complete = found.complete && bias;
    if (bias) {
      found.heading_bias_rad = bias->value;
      found.heading_bias_sigma_rad = bias->sigma;
      found.significant = found.significant ||
                          (std::abs(bias->value) >= kMinHeadingBiasRad &&
                           std::abs(bias->value) > BatchOptions::kMountingSigmas * bias->sigma);
    }
  }
  return found;
}

std::optional<MountingSignature> mounting_signature(const MountingResiduals& residuals,
                                                    const BatchOptions& options) {
  MountingSignature signature;
  if (!options.estimate_lever_arm && residuals.gnss) {
    const double size = std::hypot(residuals.gnss_mean_m[0], residuals.gnss_mean_m[1]);
    for (std::size_t a = 0; a < 2; ++a) {
      signature.lever_arm =
          signature.lever_arm ||
          (size >= kMinLeverArmM && shows(residuals.gnss_mean_m[a],
                                          residuals.gnss_standard_error_m[a], 0.5 * kMinLeverArmM));
    }
  }
  // The poses take up most of an offset that the fixes show (the antenna 0.5 m left: 0.21 m
  // left in the fixes' mean); the Doppler speed's residual shows it whole.
  if (!options.estimate_lever_arm && residuals.doppler) {
    signature.lever_arm =
        signature.lever_arm ||
        shows(residuals.doppler_left_m, residuals.doppler_left_standard_error_m, kMinLeverArmM);
  }
  signature.heading_bias =
      !options.estimate_heading_bias && residuals.heading &&
      shows(residuals.heading_mean_rad, residuals.heading_standard_error_rad, kMinHeadingBiasRad);
  if (!signature.lever_arm && !signature.heading_bias) return std::nullopt;
  return signature;
}

BatchSummary take_mounting_where_significant(BatchSummary without, BatchSummary with,
                                             const MountingSignature& signature,
                                             const BatchOptions& options) {
  BatchSummary::MountingDetection detection;
  detection.signature = without.mounting_residuals;
  detection.lever_arm = signature.lever_arm;
  detection.heading_bias = signature.heading_bias;
  detection.circumference_without_m = circumferences(without);
  detection.circumference_with_m = circumferences(with);
  const MountingFound found = mounting_found(with, signature, options);
  detection.lever_arm_m = found.lever_arm_m;
  detection.lever_arm_sigma_m = found.lever_arm_sigma_m;
  detection.heading_bias_rad = found.heading_bias_rad;
  detection.heading_bias_sigma_rad = found.heading_bias_sigma_rad;
  detection.fitted = second_fit_stood(with) && found.complete;
  detection.taken = detection.fitted && found.significant;
  BatchSummary kept = keep_one_fit(std::move(without), std::move(with), detection.taken);
  kept.mounting_detection = detection;
  return kept;
}

bool mounting_explained_by_latency(const BatchSummary& lagged, const BatchOptions& options) {
  if (!lagged.mounting_detection || !lagged.mounting_detection->taken ||
      !lagged.latency_detection || !lagged.latency_detection->taken)
    return false;
  const BatchSummary::MountingDetection& taken = *lagged.mounting_detection;
  const MountingFound found =
      mounting_found(lagged, {taken.lever_arm, taken.heading_bias}, options);
  return found.complete && !found.significant;
}

BatchSummary drop_mounting_explained_by_latency(BatchSummary lagged, BatchSummary lag_alone,
                                                const BatchOptions& options) {
  BatchSummary::MountingDetection mounting = *lagged.mounting_detection;
  BatchSummary::LatencyDetection lag = *lagged.latency_detection;
  // Taken as the latency was.
  const LatencyFound found = latency_found(
      lag_alone, options.latency_s, {lag.signature, lag.by_doppler_noise, lag.by_gnss_noise});
  if (found.taken) {
    mounting.taken = false;
    mounting.explained_by_latency = true;
    lag.latency_s = found.latency->value;
    lag.sigma_s = found.latency->sigma;
    lag.doppler_sigma_scale_with = lag_alone.doppler_sigma_scale;
    lag.gnss_sigma_scale_with = gnss_sigma_scale(lag_alone);
    lag.circumference_without_m = mounting.circumference_without_m;
  }
  BatchSummary kept = keep_one_fit(std::move(lagged), std::move(lag_alone), found.taken);
  kept.mounting_detection = mounting;
  kept.latency_detection = lag;
  return kept;
}

namespace {

std::string heading_after_report(const BatchSummary::MountingDetection& detection) {
  const BatchSummary::MountingDetection::HeadingAfter& after = *detection.heading_after;
  const bool antenna = detection.lever_arm && detection.taken;
  const char* found = after.beside_latency ? (antenna ? "the antenna and the latency (below)"
                                                      : "the latency (below)")
                                           : "the antenna";
  return fmt::format(
      "the fit with {} left heading.csv {:+.2f} deg off the fitted heading (standard error {:.2f} "
      "deg), as a mount's yaw offset leaves it, which the fits before hid (their fixes far off the "
      "path, the poses followed heading.csv); estimated beside them: heading.csv reading {:+.2f} "
      "deg (1-sigma {:.2f}) beyond the heading, which moves the circumferences by {:+.3g} / "
      "{:+.3g} mm; state it (estimate_heading_bias: true)",
      found, deg_from_rad(after.seen_rad), deg_from_rad(after.seen_standard_error_rad),
      deg_from_rad(detection.heading_bias_rad), deg_from_rad(detection.heading_bias_sigma_rad),
      1e3 * (after.circumference_with_m[0] - after.circumference_without_m[0]),
      1e3 * (after.circumference_with_m[1] - after.circumference_without_m[1]));
}

// The line without a heading found after the others.
std::string first_look_report(const BatchSummary::MountingDetection& detection) {
  const MountingResiduals& s = detection.signature;
  const bool heading_first = detection.heading_bias && !detection.heading_after;
  std::vector<std::string> seen, found, fixes;
  if (detection.lever_arm) {
    std::string doppler;
    if (s.doppler) {
      doppler =
          fmt::format(" and the Doppler speed as from {:+.2f} m left (standard error {:.3f} m)",
                      s.doppler_left_m, s.doppler_left_standard_error_m);
    }
    if (detection.by_gnss_noise) {
      seen.push_back(fmt::format(
          "the GNSS fixes' residuals {:.1f} times their configured noise, as an antenna off the "
          "rear axle's centre leaves fixes more precise than it (their means showed none)",
          detection.gnss_sigma_scale_without));
    } else {
      seen.push_back(fmt::format(
          "the GNSS fixes {:+.2f} m ahead and {:+.2f} m left of the fitted path (standard error "
          "{:.3f} / {:.3f} m){}, as an antenna off the rear axle's centre leaves them",
          s.gnss_mean_m[0], s.gnss_mean_m[1], s.gnss_standard_error_m[0],
          s.gnss_standard_error_m[1], doppler));
    }
    found.push_back(fmt::format(
        "the antenna {:+.3f} m ahead (1-sigma {:.3f}) and {:+.3f} m left (1-sigma {:.3f}) of the "
        "rear axle's centre{}",
        detection.lever_arm_m[0], detection.lever_arm_sigma_m[0], detection.lever_arm_m[1],
        detection.lever_arm_sigma_m[1],
        detection.by_gnss_noise
            ? fmt::format(", which leaves the fixes {:.1f} times", detection.gnss_sigma_scale_with)
            : std::string()));
    fixes.push_back(
        "vehicle.yaml's gnss_x_m and gnss_y_m, which layer 1 reads too (or estimate_lever_arm: "
        "true)");
  }
  if (heading_first) {
    seen.push_back(fmt::format(
        "heading.csv {:+.2f} deg off the fitted heading (standard error {:.2f} deg), as a mount's "
        "yaw offset leaves it",
        deg_from_rad(s.heading_mean_rad), deg_from_rad(s.heading_standard_error_rad)));
    found.push_back(fmt::format(
        "heading.csv reading {:+.2f} deg (1-sigma {:.2f}) beyond the heading",
        deg_from_rad(detection.heading_bias_rad), deg_from_rad(detection.heading_bias_sigma_rad)));
    fixes.push_back("estimate_heading_bias: true");
  }
  const auto joined = [](const std::vector<std::string>& parts) {
    return fmt::format("{}", fmt::join(parts, "; "));
  };
  if (detection.found_beside_latency) {
    return fmt::format(
        "{:<13}the latency's fit alone (below) left the GNSS fixes' residuals {:.1f} times their "
        "configured noise, as an antenna off the rear axle's centre beside the lag leaves them; "
        "estimated beside it: {}; with the latency these leave them {:.1f} times and move the "
        "circumferences by {:+.3g} / {:+.3g} mm; state it ({})\n",
        "mounting", detection.gnss_sigma_scale_without, joined(found),
        detection.gnss_sigma_scale_with,
        1e3 * (detection.circumference_with_m[0] - detection.circumference_without_m[0]),
        1e3 * (detection.circumference_with_m[1] - detection.circumference_without_m[1]),
        joined(fixes));
  }
  const std::string left = fmt::format("the fit without them left {}", joined(seen));
  if (!detection.fitted) {
    return fmt::format("{:<13}{}; with them estimated the fit did not stand: kept without\n",
                       "mounting", left);
  }
  if (detection.explained_by_latency) {
    return fmt::format(
        "{:<13}{}; estimated, {}; but with the latency (below) estimated beside it, that lies "
        "within {:g} sigma (or {:g} m / {:.2f} deg) of what was held: the lag showed as it, kept "
        "without\n",
        "mounting", left, joined(found), BatchOptions::kMountingSigmas, kMinLeverArmM,
        deg_from_rad(kMinHeadingBiasRad));
  }
  if (!detection.taken) {
    return fmt::format(
        "{:<13}{}; estimated, {} lies within {:g} sigma (or {:g} m / {:.2f} deg) of what was held: "
        "kept without\n",
        "mounting", left, joined(found), BatchOptions::kMountingSigmas, kMinLeverArmM,
        deg_from_rad(kMinHeadingBiasRad));
  }
  return fmt::format(
      "{:<13}{}; estimated: {}, which moves the circumferences by {:+.3g} / {:+.3g} mm; state it "
      "({})\n",
      "mounting", left, joined(found),
      1e3 * (detection.circumference_with_m[0] - detection.circumference_without_m[0]),
      1e3 * (detection.circumference_with_m[1] - detection.circumference_without_m[1]),
      joined(fixes));
}

}  // namespace

std::string mounting_detection_report(const BatchSummary::MountingDetection& detection) {
  if (!detection.heading_after) return first_look_report(detection);
  if (!detection.lever_arm)
    return fmt::format("{:<13}{}\n", "mounting", heading_after_report(detection));
  std::string line = first_look_report(detection);
  line.pop_back();  // its newline
  return fmt::format("{}; then {}\n", line, heading_after_report(detection));
}

}  // namespace odocal::batch
