// An antenna off the rear axle's centre that precise fixes show by their noise and not by their
// residuals' means: the poses and the turn terms take the means, and the noise adaptation takes the
// rest (RTK fixes, the built-in urban drive without a Doppler column, the antenna 0.23 m behind and
// 0.48 m right: the fixes 1.4 times their noise, the regression terms' turn dependence taking the
// lever arm, -6.7 mm at a sigma of 5 mm; a lag beside it hides it the same way). calibrate_batch
// fits the log again with the lever arm estimated and takes that fit only where it explains the
// fixes.
#pragma once

#include "odocal/estimation/batch_calibration.hpp"

namespace odocal::batch {

// The fit's fixes lie kLagGnssExplained times their configured noise or more off the path, no
// lever arm is estimated, and none was fitted for the residuals' means.
bool lever_arm_worth_fitting_by_fixes(const BatchSummary& summary, const BatchOptions& fitted);

// `with`: the log calibrated with the lever arm estimated besides what `without` estimated. It
// stands where the lever arm explains the fixes (below); then it carries the lever arm in
// mounting_detection (by_gnss_noise), beside a heading bias taken before. Otherwise `without`.
BatchSummary take_lever_arm_by_fixes(BatchSummary without, BatchSummary with,
                                     const BatchOptions& options);

// A significant lag whose fit left the fixes beyond kLagGnssExplained: looked for by their noise
// and not taken (not a lag's alone), or taken by another sign (the Doppler speed's dependence:
// an antenna 1.98 m ahead beside 65 ms, the latency found as 50 ms and the fixes 1.9 times their
// noise); with no lever arm estimated or taken (a heading bias taken stays in both fits; the
// urban drive with RTK fixes 132 ms late, the
// antenna 0.27 m behind and 0.39 m right: the latency alone 173 ms leaving the fixes 1.4 times
// their noise; with the lever arm beside it 132 ms, 1.0 times).
bool lever_arm_worth_fitting_beside_latency(const BatchSummary& lag_fit,
                                            const BatchOptions& fitted);

// `both`: the log calibrated with the latency and the lever arm estimated. It stands where the
// latency is taken as the lag's sign asks (latency_found) and the lever arm
// explains the fixes; then it carries both as found (mounting_detection.found_beside_latency,
// beside a heading bias taken before).
// Otherwise `lag_fit` (the summary the latency detection returned) stands.
BatchSummary take_lever_arm_beside_latency(BatchSummary lag_fit, BatchSummary both,
                                           const BatchOptions& options);

}  // namespace odocal::batch
