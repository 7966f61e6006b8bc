#include "lever_arm_by_fixes.hpp"

#include <array>
#include <utility>

#include "latency_detection.hpp"
#include "mounting_detection.hpp"
#include "second_fit.hpp"

namespace odocal::batch {

namespace {

// The lever arm lies beyond kMountingSigmas of its sigma (and kMinLeverArmM) from the stated, its
// fit leaves the fixes under kLagGnssExplained, and that fit's own residuals say its model explains
// the log: a model that misfits hands its misfit to a lever arm as readily (a plain fit of the
// circuit with a body lower and heavier than stated, a latency beside it: an antenna 3.4 m ahead
// and 320 ms, the fixes as configured).
bool lever_arm_explains_fixes(const BatchSummary& with, const MountingFound& found) {
  return second_fit_stood(with) && found.complete && found.significant &&
         gnss_sigma_scale(with) < kLagGnssExplained && with.model_adequacy.judged &&
         with.model_adequacy.explains;
}

// The detection with the lever arm found in `with` added: to a heading bias taken before, whose
// fit with neither stays the "without" and whose value is `with`'s; or anew, against `without`.
BatchSummary::MountingDetection with_lever_arm(const BatchSummary& without,
                                               const BatchSummary& with,
                                               const MountingFound& found) {
  BatchSummary::MountingDetection detection;
  if (without.mounting_detection && without.mounting_detection->taken) {
    detection = *without.mounting_detection;
    if (const EstimatedParameter* bias = estimated_parameter(with, "heading_bias_rad")) {
      detection.heading_bias_rad = bias->value;
      detection.heading_bias_sigma_rad = bias->sigma;
    }
  } else {
    detection.signature = without.mounting_residuals;
    detection.circumference_without_m = circumferences(without);
    detection.fitted = detection.taken = true;
  }
  detection.lever_arm = true;
  detection.lever_arm_m = found.lever_arm_m;
  detection.lever_arm_sigma_m = found.lever_arm_sigma_m;
  return detection;
}

}  // namespace

bool lever_arm_worth_fitting_by_fixes(const BatchSummary& summary, const BatchOptions& fitted) {
  const auto& mounting = summary.mounting_detection;
  return !fitted.estimate_lever_arm && summary.mounting_residuals.gnss &&
         gnss_sigma_scale(summary) >= kLagGnssExplained &&
         !(mounting && mounting->lever_arm && mounting->fitted);
}

BatchSummary take_lever_arm_by_fixes(BatchSummary without, BatchSummary with,
                                     const BatchOptions& options) {
  const MountingFound found = mounting_found(with, {.lever_arm = true}, options);
  if (!lever_arm_explains_fixes(with, found))
    return keep_one_fit(std::move(without), std::move(with), false);
  BatchSummary::MountingDetection detection = with_lever_arm(without, with, found);
  detection.by_gnss_noise = true;
  detection.gnss_sigma_scale_without = gnss_sigma_scale(without);
  detection.gnss_sigma_scale_with = gnss_sigma_scale(with);
  detection.circumference_with_m = circumferences(with);
  BatchSummary kept = keep_one_fit(std::move(without), std::move(with), true);
  kept.mounting_detection = detection;
  return kept;
}

bool lever_arm_worth_fitting_beside_latency(const BatchSummary& lag_fit,
                                            const BatchOptions& fitted) {
  const auto& lag = lag_fit.latency_detection;
  const auto& mounting = lag_fit.mounting_detection;
  if (!lag || !lag->significant || fitted.estimate_lever_arm ||
      (mounting && mounting->taken && mounting->lever_arm))
    return false;
  // Not taken as the fixes' noise's alone, or taken by another sign and leaving them wide.
  return lag->taken ? gnss_sigma_scale(lag_fit) >= kLagGnssExplained : lag->by_gnss_noise;
}

BatchSummary take_lever_arm_beside_latency(BatchSummary lag_fit, BatchSummary both,
                                           const BatchOptions& options) {
  BatchSummary::LatencyDetection lag = *lag_fit.latency_detection;
  const LatencyFound latency = latency_found(
      both, options.latency_s, {lag.signature, lag.by_doppler_noise, lag.by_gnss_noise});
  const MountingFound found = mounting_found(both, {.lever_arm = true}, options);
  if (!latency.taken || !lever_arm_explains_fixes(both, found))
    return keep_one_fit(std::move(lag_fit), std::move(both), false);
  BatchSummary::MountingDetection mounting = with_lever_arm(lag_fit, both, found);
  // Against the fit without the latency, as the latency is (a heading taken before: with neither).
  if (!mounting.heading_bias) mounting.circumference_without_m = lag.circumference_without_m;
  mounting.circumference_with_m = circumferences(both);
  mounting.found_beside_latency = true;
  mounting.gnss_sigma_scale_without = lag.gnss_sigma_scale_with;
  mounting.gnss_sigma_scale_with = gnss_sigma_scale(both);
  lag.latency_s = latency.latency->value;
  lag.sigma_s = latency.latency->sigma;
  lag.taken = true;
  lag.doppler_sigma_scale_with = both.doppler_sigma_scale;
  lag.gnss_sigma_scale_with = mounting.gnss_sigma_scale_with;
  BatchSummary kept = keep_one_fit(std::move(lag_fit), std::move(both), true);
  kept.mounting_detection = mounting;
  kept.latency_detection = lag;
  return kept;
}

}  // namespace odocal::batch
