// A heading.csv mounted at a yaw that the first fits' residuals did not show: where their fixes
// lie far off the path (a lag, an antenna off the centre), the noise adaptation widens them and
// the poses' heading follows heading.csv, offset and all (the RTK urban drive, fixes 149 ms late,
// the antenna 2.9 m ahead and 0.58 m left, heading.csv 0.071 rad off: the first fit's fixes 53
// times their noise; the latency's fit left them 3.9 times and the heading's residual 0.0056 rad
// at a standard error of 0.0012). The fit that the latency and the lever arm leave holds the poses
// to the fixes again and shows it (0.067 rad at 0.0013); calibrate_batch looks at it again there
// and fits the log with the heading bias estimated beside what that fit estimated.
#pragma once

#include "odocal/estimation/batch_calibration.hpp"

namespace odocal::batch {

// `returned` was fitted with `options` after the first fit's mounting residuals were looked at
// (`first` its options): it estimates a latency or a lever arm the first did not, no heading bias,
// none was fitted before, and its residuals show one (mounting_signature).
bool heading_worth_fitting_after(const BatchSummary& returned, const BatchOptions& options,
                                 const BatchOptions& first);

// `with`: the log calibrated with the heading bias estimated beside what `without` estimated. It
// stands where the bias is significant (mounting_found); then it carries the bias in
// mounting_detection (heading_after, beside what was found before). Otherwise `without`.
BatchSummary take_heading_after(BatchSummary without, BatchSummary with,
                                const BatchOptions& options);

}  // namespace odocal::batch
