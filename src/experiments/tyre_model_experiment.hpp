#pragma once
// Beyond the paper (issue 17): the batch estimator with the plain two-wheel model, the extended
// tyre model and `auto` on the section 5 scenario, realistic mode, driven by a rear- and a
// front-wheel-drive car; `auto` on the ideal drive (where it must keep the plain model); and the
// held-out drift of the realistic urban drive. Every figure beside the target.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "experiments/paper_setup.hpp"

namespace odocal::experiments {

// Bump when the tyre model or its fit changes what these pieces write (their cache key). 3: the
// physical terms and auto; 6: the side slip; 7: auto's agreement with the plain fit; 8: the urban
// drift with the tick counts smoothed, and without; 9: held coefficients in the sigma; 10: held
// at a car's value; 11: the urban drive with exact wheels and the reference's own uncertainty;
// 12: held regression terms in the sigma; 13: the grip-sharing driver beside the circuit's;
// 14: a free-rolling axle's drive slip held at zero; 15: sigma widened by the odometry misfit;
// 16: a reverted GNSS noise adaptation's first estimate standing as it was; 17: auto refuses a
// tyre model that the plain model with the track width freed fits as well; 18: where auto doubts
// the track, each tyre model fitted both ways, and the plain model with it free where no tyre
// model stands; 19: a freed track only where it dead-reckons the log better than the stated one;
// 20: GNSS noise adaptation on top of a stated correlated error, and a reverted adaptation's
// Gauss-Markov states at zero; 21: the accelerometer's heading walk, and the grip-sharing drives
// again with an automotive-grade accelerometer; 22: the physical terms' slip divides the
// circumference (c / (1 + kappa), not c (1 - kappa)); 23: a physical slip coefficient judged as
// itself (at most 0.1), not by its effect at the log's RMS state; 24: a plain fit that a model
// which is no tyre explains decisively better carries its gap to it; 25: the physical terms
// witnessed by the regression terms; 26: and to a tyre fit that holds every coefficient; 27: a
// latency that a tyre fit's residuals show, estimated; 28: the witness only where the physical
// fit's answer stands; 29: the regression terms chosen by hand judged by the physical ones (the
// experiment's fits are unjudged: nothing moved); 30: the accelerometer's forward offset taken
// out at the stops, and what is left of it in the physical terms' sigma; 31: only where it
// stands out of its sigma; 32: the mounting looked for in the residuals (detect_mounting); 33:
// the rear wheels' tick difference smoothed before the batch (heading_tick_smoothing_s); 34: with
// a local quadratic over +-0.25 s in place of the line over +-0.1 s.
inline constexpr int kTyreModelExperimentVersion = 34;

// {seed, realistic: {rear: {none, extended, physical, auto}, front: {...}}, ideal: {none, auto},
// grip_sharing: {rear: {auto}, front: {auto}}, grip_sharing_quiet_accelerometer: {rear: {auto},
// front: {auto}}, grip_sharing_ideal: {none}} with
// method_run_to_json entries, each with "tyre_model_used" (whether the result carries one); the
// grip_sharing runs are the same drives with a driver who shares the grip with the turn and has
// a sedan's power (docs/simulator.md, "Driver").
nlohmann::json run_tyre_model_seed(const PaperSetup& setup, std::uint64_t seed);

// {seed, nominal/calibrated median drift %, windows, tyre_model_used}: the built-in urban drive
// (realistic, rear-wheel drive) calibrated by the batch with tyre_model auto, then `validate`'s
// 60 s windows (one every 10 s) dead-reckoned from the smoothed reference; beside it the same
// with the true circumferences at rest, and with them on the drive in ideal mode (the metric's
// floor: the reference's and the encoders' noise).
nlohmann::json run_urban_drift_seed(std::uint64_t seed);

// Per drivetrain and model: mean |error|, share inside 3 reported sigma, mean whole-log dead
// reckoning, mean time; the ideal-mode comparison; the urban drift median; each target and
// whether it is met.
nlohmann::json summarise_tyre_models(const std::vector<nlohmann::json>& seeds,
                                     const std::vector<nlohmann::json>& urban);

}  // namespace odocal::experiments
