#include "batch_detections.hpp"

#include <optional>
#include <utility>

#include "heading_after_fit.hpp"
#include "latency_detection.hpp"
#include "lever_arm_by_fixes.hpp"
#include "mounting_detection.hpp"

namespace odocal::batch {

Calibrated detect_mounting(const Calibrate& calibrate, BatchSummary summary,
                           const BatchOptions& first) {
  BatchOptions fitted = first;
  if (!first.detect_mounting) return {std::move(summary), fitted};
  // A mounting first: an antenna off the rear axle's centre is no lag, and a lag is looked for
  // with it in place.
  if (const auto signature = mounting_signature(summary.mounting_residuals, first)) {
    BatchOptions mounted = first;
    mounted.estimate_lever_arm = first.estimate_lever_arm || signature->lever_arm;
    mounted.estimate_heading_bias = first.estimate_heading_bias || signature->heading_bias;
    summary =
        take_mounting_where_significant(std::move(summary), calibrate(mounted), *signature, first);
    if (summary.mounting_detection->taken) fitted = mounted;
  }
  // Precise fixes whose means the poses took: their noise shows an antenna off the centre.
  if (lever_arm_worth_fitting_by_fixes(summary, fitted)) {
    BatchOptions with_lever_arm = fitted;
    with_lever_arm.estimate_lever_arm = true;
    summary = take_lever_arm_by_fixes(std::move(summary), calibrate(with_lever_arm), fitted);
    if (summary.mounting_detection && summary.mounting_detection->by_gnss_noise)
      fitted = with_lever_arm;
  }
  return {std::move(summary), fitted};
}

Calibrated detect_latency(const Calibrate& calibrate, Calibrated mounted,
                          const BatchOptions& unmounted, const BatchOptions& options, bool judged) {
  if (!options.detect_latency || options.estimate_latency || !judged) return mounted;
  const std::optional<LagSignature> signature = lag_signature(mounted.summary);
  if (!signature) return mounted;
  BatchOptions lagged = mounted.options;
  lagged.estimate_latency = true;
  // The latency's fit holds the mounting found before it: what was found carries over.
  auto mounting_detection = mounted.summary.mounting_detection;
  BatchSummary result = take_latency_where_significant(
      std::move(mounted.summary), calibrate(lagged), *signature, options.latency_s);
  result.mounting_detection = std::move(mounting_detection);
  const bool latency_taken = result.latency_detection && result.latency_detection->taken;
  const BatchOptions& result_options = latency_taken ? lagged : mounted.options;
  // Precise fixes that a lag alone does not explain: an antenna off the centre beside it.
  if (lever_arm_worth_fitting_beside_latency(result, mounted.options)) {
    BatchOptions both = lagged;
    both.estimate_lever_arm = true;
    result = take_lever_arm_beside_latency(std::move(result), calibrate(both), options);
    const bool found = result.mounting_detection && result.mounting_detection->found_beside_latency;
    return {std::move(result), found ? both : result_options};
  }
  // A lag shows in the fixes as an antenna behind the axle: where the mounting taken is no longer
  // significant beside the latency, the log is calibrated with the latency alone.
  if (!mounting_explained_by_latency(result, options)) return {std::move(result), result_options};
  BatchOptions lag_alone = unmounted;
  lag_alone.estimate_latency = true;
  result = drop_mounting_explained_by_latency(std::move(result), calibrate(lag_alone), options);
  const bool dropped = result.mounting_detection && result.mounting_detection->explained_by_latency;
  return {std::move(result), dropped ? lag_alone : result_options};
}

BatchSummary detect_heading_after(const Calibrate& calibrate, Calibrated result,
                                  const BatchOptions& first) {
  if (!first.detect_mounting || !heading_worth_fitting_after(result.summary, result.options, first))
    return std::move(result.summary);
  BatchOptions with_heading = result.options;
  with_heading.estimate_heading_bias = true;
  return take_heading_after(std::move(result.summary), calibrate(with_heading), result.options);
}

}  // namespace odocal::batch
