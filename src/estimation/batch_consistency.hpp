#pragma once
// The batch calibration's split-sample check (BatchOptions::consistency_parts): the log
// calibrated again in consecutive parts, and the whole log's circumferences' sigma widened where
// the parts disagree beyond theirs (docs/batch-calibration.md, "A check that sees it").

#include "odocal/data/log.hpp"
#include "odocal/estimation/batch_calibration.hpp"

namespace odocal::batch {

// Fills summary.consistency and widens the circumferences' sigma (covariance, parameters,
// reference circumference) by the Birge ratio where it is above its bound; a widened sigma above
// max_sigma_circumference_m makes the result not identified. Only for a usable summary.
void check_parts_consistency(const Log& log, const BatchOptions& options,
                             const CalibrationOptions& common, BatchSummary& summary);

// The ratio sqrt(q / dof) below which the chi-square statistic of `dof` degrees of freedom stays
// with 95 % probability (Wilson-Hilferty's approximation of its quantile q: 1.3 % low at 1 degree
// of freedom, within 0.5 % from 2 on).
double birge_ratio_bound(int dof);

}  // namespace odocal::batch
