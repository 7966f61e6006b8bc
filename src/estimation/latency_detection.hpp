// BatchOptions::detect_latency: a lag between the GNSS and the wheels that the fit did not
// estimate leaves an along-track (or Doppler speed) residual of -latency x a_x, which the tyre
// terms read as slip (comma2k19's minute, its receiver's fixes stamped 0.1 s after the wheel
// speeds of the same moment: the physical terms 6.5 mm below the reference pose's scale at a
// sigma of 1.15 mm with vehicle.yaml stating the car front-driven; the simulated circuit,
// front-driven, with a 90 ms receiver latency: -9.7 mm at a sigma of 3.6 mm). Where the fit's
// residuals show that signature, calibrate_batch fits the log again with the latency estimated
// and takes that fit where the latency it finds is significant.
#pragma once

#include <optional>
#include <string>

#include "odocal/estimation/batch_calibration.hpp"

namespace odocal::batch {

// The dependence a lag leaves in the fit's residuals: along-track or Doppler speed against the
// longitudinal acceleration, as the model-adequacy judgement counts it (none: not there).
std::optional<ResidualDependence> lag_signature(const ModelAdequacy& adequacy);

// The fit with the latency estimated where the latency lies beyond
// BatchOptions::kLatencySigmas of its sigma, the fit without it otherwise; either carries what was
// found (BatchSummary::latency_detection) and the other's solves.
BatchSummary take_latency_where_significant(BatchSummary without, BatchSummary with,
                                            const ResidualDependence& signature);

// The report's line on it; `estimate` the summary's.
std::string latency_detection_report(const BatchSummary::LatencyDetection& detection,
                                     const OdometryParams& estimate);

}  // namespace odocal::batch
