#pragma once
// The batch maximum-likelihood calibration behind `calibrate(..., method = kBatch)`.

#include "odocal/estimation/calibration.hpp"

namespace odocal {

// Fills result.estimate, covariance, parameters, identifiability, solver_report, termination.
// `result.nominal` must be set. Poses start from the layer-1 reference, parameters from nominal.
void run_batch(const Log& log, const ReferenceTrajectory& reference,
               const CalibrationOptions& options, CalibrationResult& result);

}  // namespace odocal
