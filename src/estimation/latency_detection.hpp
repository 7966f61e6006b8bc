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

// A lag of tau leaves tau a_x in the Doppler speed's error (145 ms at 2 m/s^2: 0.29 m/s against a
// configured 0.05), so the noise adaptation widens it. Where the regression terms took up the rest
// of the signature (the urban drive with the fixes 145 ms late and heading.csv 4 deg off: the
// physical terms no tyre with the lag in, the regression terms' residuals following nothing, the
// Doppler noise 5.5 times the configured, refused at a sigma of 19 mm), that is what is left.
inline constexpr double kLagDopplerScale = 2.0;

// Fixes more precise than the lag leaves them: RTK's 2 cm stamped 150 ms late are 0.95 m RMS off
// the fitted path at the urban drive's speeds, which the noise adaptation took for a correlated
// error of the receiver (sigma x35), the fit plain and no dependence counted. Where the fixes'
// residuals are this many times the configured noise or more, a latency is looked for.
inline constexpr double kLagGnssScale = 2.0;
// ... and a latency looked for by it is taken only where it is the whole of the widening: its
// fit leaves the fixes within this scale of their configured noise, the band in which the noise
// adaptation leaves a white noise as configured. A misfit widens them too, and a latency takes
// some of it: the plain model on tyres far softer than a road tyre's left 2.2 times, 1.56 with a
// latency of 327 ms at 9 sigma; on the ideal circuit with condition-dependent tyres 3.2 times,
// 1.58 with 96 ms at 8 sigma. RTK fixes 150 ms late: 47.6 times, 1.0 with it.
inline constexpr double kLagGnssExplained = 1.25;

// The fixes' residual RMS over their configured noise (GnssNoiseReport: the adapted model's where
// the noise was adapted).
double gnss_sigma_scale(const BatchSummary& summary);

// The dependence a lag leaves in the fit's residuals: along-track or Doppler speed against the
// longitudinal acceleration, as the model-adequacy judgement counts it (only in a fit whose tyre
// terms take the slip, which leaves the same signature); or, where none counts but the Doppler
// speed's noise was widened kLagDopplerScale times or more, the Doppler speed's dependence as it
// stands (`by_doppler_noise`); or, under any model, the fixes' residuals kLagGnssScale times
// their configured noise or more (`by_gnss_noise`). None: neither is there.
struct LagSignature {
  ResidualDependence dependence;
  bool by_doppler_noise{}, by_gnss_noise{};
};
std::optional<LagSignature> lag_signature(const BatchSummary& summary);

// What a fit with the latency estimated found: the latency (null where the fit did not stand or
// has none), whether it lies beyond BatchOptions::kLatencySigmas of its sigma from `stated_s`,
// and whether it is taken: significant and, where a noise was the sign it was looked for by,
// bringing that noise under its scale (a model that misfits the log widens the noise too, and a
// latency takes some of any misfit); the fixes' under kLagGnssExplained.
struct LatencyFound {
  const EstimatedParameter* latency{};
  bool significant{}, taken{};
};
LatencyFound latency_found(const BatchSummary& with, double stated_s,
                           const LagSignature& signature);

// The fit with the latency estimated where the latency lies beyond
// BatchOptions::kLatencySigmas of its sigma from the one stated (BatchOptions::latency_s), the fit
// without it otherwise; either carries what was found (BatchSummary::latency_detection) and the
// other's solves.
BatchSummary take_latency_where_significant(BatchSummary without, BatchSummary with,
                                            const LagSignature& signature, double stated_s);

// The report's line on it; `estimate` the summary's.
std::string latency_detection_report(const BatchSummary::LatencyDetection& detection,
                                     const OdometryParams& estimate);

}  // namespace odocal::batch
