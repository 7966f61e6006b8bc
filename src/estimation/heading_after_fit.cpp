#include "heading_after_fit.hpp"

#include <array>
#include <utility>

#include "mounting_detection.hpp"
#include "second_fit.hpp"

namespace odocal::batch {

namespace {

// What `without` found, its values those of `with` (fitted again beside the heading bias).
void refresh_found_values(const BatchSummary& with, const BatchOptions& options,
                          BatchSummary::MountingDetection* mounting,
                          BatchSummary::LatencyDetection* latency) {
  if (mounting && mounting->taken && mounting->lever_arm) {
    const MountingFound arm = mounting_found(with, {.lever_arm = true}, options);
    if (arm.complete) {
      mounting->lever_arm_m = arm.lever_arm_m;
      mounting->lever_arm_sigma_m = arm.lever_arm_sigma_m;
    }
  }
  if (latency && latency->taken) {
    if (const EstimatedParameter* lag = estimated_parameter(with, "latency_s")) {
      latency->latency_s = lag->value;
      latency->sigma_s = lag->sigma;
    }
  }
}

}  // namespace

bool heading_worth_fitting_after(const BatchSummary& returned, const BatchOptions& options,
                                 const BatchOptions& first) {
  const bool fitted_more = (options.estimate_latency && !first.estimate_latency) ||
                           (options.estimate_lever_arm && !first.estimate_lever_arm);
  const auto& mounting = returned.mounting_detection;
  if (!fitted_more || options.estimate_heading_bias || (mounting && mounting->heading_bias))
    return false;
  const std::optional<MountingSignature> signature =
      mounting_signature(returned.mounting_residuals, options);
  return signature && signature->heading_bias;
}

BatchSummary take_heading_after(BatchSummary without, BatchSummary with,
                                const BatchOptions& options) {
  const MountingFound found = mounting_found(with, {.heading_bias = true}, options);
  if (!second_fit_stood(with) || !found.complete || !found.significant)
    return keep_one_fit(std::move(without), std::move(with), false);
  BatchSummary::MountingDetection mounting;
  if (without.mounting_detection) {
    mounting = *without.mounting_detection;
  } else {
    mounting.signature = without.mounting_residuals;
    mounting.circumference_without_m = circumferences(without);
    mounting.circumference_with_m = circumferences(with);
    mounting.fitted = mounting.taken = true;
  }
  std::optional<BatchSummary::LatencyDetection> latency = without.latency_detection;
  refresh_found_values(with, options, &mounting, latency ? &*latency : nullptr);
  mounting.heading_bias = true;
  mounting.heading_bias_rad = found.heading_bias_rad;
  mounting.heading_bias_sigma_rad = found.heading_bias_sigma_rad;
  mounting.heading_after = BatchSummary::MountingDetection::HeadingAfter{
      .beside_latency = latency && latency->taken,
      .seen_rad = without.mounting_residuals.heading_mean_rad,
      .seen_standard_error_rad = without.mounting_residuals.heading_standard_error_rad,
      .circumference_without_m = circumferences(without),
      .circumference_with_m = circumferences(with)};
  BatchSummary kept = keep_one_fit(std::move(without), std::move(with), true);
  kept.mounting_detection = mounting;
  kept.latency_detection = std::move(latency);
  return kept;
}

}  // namespace odocal::batch
