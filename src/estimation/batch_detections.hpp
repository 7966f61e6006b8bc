// The batch's detections in the order calibrate_batch runs them (docs/batch-calibration.md, "The
// mounting the log shows", "A latency the log shows" and its sections): a mounting first, as the
// first fit's residuals (or its fixes' noise) show it; then a latency, with what was found in
// place, and an antenna beside it; then a heading bias that the first fits hid and the last one
// shows. Each fits the log again only where its sign shows, and takes that fit only where what it
// found stands.
#pragma once

#include <functional>

#include "odocal/estimation/batch_calibration.hpp"

namespace odocal::batch {

// The log calibrated as configured with these options (calibrate_batch's own preparation).
using Calibrate = std::function<BatchSummary(const BatchOptions&)>;

// A fit and the options it was fitted with.
struct Calibrated {
  BatchSummary summary;
  BatchOptions options;
};

// `summary`: the log fitted with `first` (detect_mounting: looked for only where set).
Calibrated detect_mounting(const Calibrate& calibrate, BatchSummary summary,
                           const BatchOptions& first);

// `mounted`: what detect_mounting returned; `unmounted` the options before it, `options` as
// configured; `judged`: CalibrationOptions::judge_model_adequacy (a latency is looked for only
// then).
Calibrated detect_latency(const Calibrate& calibrate, Calibrated mounted,
                          const BatchOptions& unmounted, const BatchOptions& options, bool judged);

// `result`: what detect_latency returned; the summary calibrate_batch returns
// (heading_after_fit.hpp).
BatchSummary detect_heading_after(const Calibrate& calibrate, Calibrated result,
                                  const BatchOptions& first);

}  // namespace odocal::batch
