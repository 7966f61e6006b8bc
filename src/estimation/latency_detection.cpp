#include "latency_detection.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <utility>

#include "second_fit.hpp"

namespace odocal::batch {

double gnss_sigma_scale(const BatchSummary& summary) {
  const GnssNoiseReport& noise = summary.gnss_noise;
  return noise.configured_sigma_m > 0.0 ? noise.residual_sigma_m / noise.configured_sigma_m : 1.0;
}

std::optional<LagSignature> lag_signature(const BatchSummary& summary) {
  std::optional<ResidualDependence> strongest, doppler, along_track;
  for (const ResidualDependence& d : summary.model_adequacy.dependences) {
    const bool lag_shows_here = d.residual == "along-track" || d.residual == "Doppler speed";
    if (!lag_shows_here || d.quantity != "longitudinal acceleration") continue;
    (d.residual == "Doppler speed" ? doppler : along_track) = d;
    if (!d.counts()) continue;
    if (!strongest || std::abs(d.correlation) > std::abs(strongest->correlation)) strongest = d;
  }
  // The plain model's residuals follow a_x where the wheels slip, the lag's signature too, and
  // its Doppler noise widens with the slip: only a fit whose tyre terms take the slip tells them
  // apart by either (the realistic urban drive, rear-driven, the plain model: the latency took
  // the slip). The fixes' noise is the poses' to follow, slip or none.
  const bool tyre_terms = !summary.tyre_model.plain();
  if (tyre_terms && strongest) return LagSignature{*strongest};
  if (tyre_terms && summary.doppler_sigma_scale >= kLagDopplerScale) {
    return LagSignature{doppler.value_or(ResidualDependence{"Doppler speed",
                                                            "longitudinal acceleration", 0.0, 0.0}),
                        true};
  }
  if (gnss_sigma_scale(summary) >= kLagGnssScale) {
    return LagSignature{along_track.value_or(ResidualDependence{
                            "along-track", "longitudinal acceleration", 0.0, 0.0}),
                        false, true};
  }
  return std::nullopt;
}

LatencyFound latency_found(const BatchSummary& with, double stated_s,
                           const LagSignature& signature) {
  LatencyFound found;
  if (!second_fit_stood(with)) return found;
  found.latency = estimated_parameter(with, "latency_s");
  if (!found.latency) return found;
  found.significant = std::abs(found.latency->value - stated_s) >
                      BatchOptions::kLatencySigmas * found.latency->sigma;
  // The realistic circuit, rear-driven, the regression terms chosen by hand: the Doppler noise
  // 56 times the configured, a latency of 39 ms at 10 sigma, the noise 14 times with it.
  found.taken = found.significant &&
                (!signature.by_doppler_noise || with.doppler_sigma_scale < kLagDopplerScale) &&
                (!signature.by_gnss_noise || gnss_sigma_scale(with) < kLagGnssExplained);
  return found;
}

BatchSummary take_latency_where_significant(BatchSummary without, BatchSummary with,
                                            const LagSignature& signature, double stated_s) {
  BatchSummary::LatencyDetection detection{signature.dependence};
  detection.doppler_sigma_scale = without.doppler_sigma_scale;
  detection.by_doppler_noise = signature.by_doppler_noise;
  detection.gnss_sigma_scale = gnss_sigma_scale(without);
  detection.by_gnss_noise = signature.by_gnss_noise;
  detection.latency_s = detection.sigma_s = std::numeric_limits<double>::quiet_NaN();
  detection.circumference_without_m = circumferences(without);
  if (const LatencyFound found = latency_found(with, stated_s, signature); found.latency) {
    detection.latency_s = found.latency->value;
    detection.sigma_s = found.latency->sigma;
    detection.significant = found.significant;
    detection.taken = found.taken;
    detection.doppler_sigma_scale_with = with.doppler_sigma_scale;
    detection.gnss_sigma_scale_with = gnss_sigma_scale(with);
  }
  BatchSummary kept = keep_one_fit(std::move(without), std::move(with), detection.taken);
  kept.latency_detection = detection;
  return kept;
}

namespace {

std::string what_showed_it(const BatchSummary::LatencyDetection& detection) {
  const ResidualDependence& s = detection.signature;
  if (detection.by_doppler_noise) {
    return fmt::format(
        "the fit without it left the Doppler speed's noise {:.1f} times the configured (its "
        "residual against the longitudinal acceleration: rho = {:.2f}), as a lag between the GNSS "
        "and the wheels widens it",
        detection.doppler_sigma_scale, s.correlation);
  }
  if (detection.by_gnss_noise) {
    return fmt::format(
        "the fit without it left the GNSS fixes' residuals {:.1f} times their configured noise, "
        "as a lag between the GNSS and the wheels leaves fixes that are more precise than it "
        "off the path",
        detection.gnss_sigma_scale);
  }
  return fmt::format(
      "the fit without it left the {} residual following the longitudinal acceleration (rho = "
      "{:.2f}), as a lag between the GNSS and the wheels does",
      s.residual, s.correlation);
}

// The noise a latency taken by a widened noise must bring under its scale: how the report names
// it, its scale with the latency, and what a latency that leaves it wide is not.
struct WidenedNoise {
  const char* stays;
  double scale_with;
  const char* not_whose;
};
WidenedNoise widened_noise(const BatchSummary::LatencyDetection& detection) {
  if (detection.by_gnss_noise)
    return {"the fixes' residuals stay", detection.gnss_sigma_scale_with, "a lag's alone"};
  return {"the Doppler speed's noise stays", detection.doppler_sigma_scale_with, "a lag's"};
}

}  // namespace

std::string latency_detection_report(const BatchSummary::LatencyDetection& detection,
                                     const OdometryParams& estimate) {
  const std::string seen = what_showed_it(detection);
  if (!std::isfinite(detection.latency_s)) {
    return fmt::format("{:<13}{}; with the latency estimated the fit did not stand: kept without\n",
                       "latency", seen);
  }
  const double sigmas = std::abs(detection.latency_s) / detection.sigma_s;
  if (detection.significant && !detection.taken) {
    const WidenedNoise noise = widened_noise(detection);
    return fmt::format(
        "{:<13}{}; estimated, {:.1f} ms (1-sigma {:.1f} ms), but {} {:.1f} times the configured "
        "with it: not {}, kept without the latency\n",
        "latency", seen, 1e3 * detection.latency_s, 1e3 * detection.sigma_s, noise.stays,
        noise.scale_with, noise.not_whose);
  }
  if (!detection.taken) {
    const bool by_noise = detection.by_doppler_noise || detection.by_gnss_noise;
    return fmt::format(
        "{:<13}{}; estimated, {:.1f} ms (1-sigma {:.1f} ms) is within {:g} sigma of none: the {}, "
        "kept without the latency\n",
        "latency", seen, 1e3 * detection.latency_s, 1e3 * detection.sigma_s,
        BatchOptions::kLatencySigmas,
        by_noise ? "noise is not a lag's" : "dependence is the model's");
  }
  return fmt::format(
      "{:<13}{}; estimated: the GNSS fixes {} the wheels by {:.1f} ms (1-sigma {:.1f} ms, {:.0f} "
      "sigma), which moves the circumferences by {:+.3g} / {:+.3g} mm to these; align the log's "
      "clocks, or set estimate_latency: true\n",
      "latency", seen, detection.latency_s > 0.0 ? "lag" : "lead",
      1e3 * std::abs(detection.latency_s), 1e3 * detection.sigma_s, sigmas,
      1e3 * (estimate.circumference_rl_m - detection.circumference_without_m[0]),
      1e3 * (estimate.circumference_rr_m - detection.circumference_without_m[1]));
}

}  // namespace odocal::batch
