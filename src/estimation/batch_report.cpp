// The batch calibration's full text report (odocal calibrate prints it).
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

#include "batch_body_uncertainty.hpp"
#include "batch_fit.hpp"
#include "calibration_report.hpp"
#include "latency_detection.hpp"
#include "mounting_detection.hpp"
#include "odocal/estimation/batch_calibration.hpp"

namespace odocal {

std::string BatchSummary::full_report() const {
  std::string text = report_heading(*this);
  for (const EstimatedParameter& p : parameters) {
    if (!p.estimated || p.name.starts_with("circumference")) continue;
    text += fmt::format("{:<13}{} = {:.6g} (1-sigma {:.3g}{}{})\n", "parameter", p.name, p.value,
                        p.sigma, p.identified && !p.verdict.empty() ? "; " : "",
                        p.identified ? p.verdict : "");
  }
  text += fmt::format("{:<13}{}\n", "observable", identifiability);
  if (odometry_scales) {
    const OdometryScales& s = *odometry_scales;
    text += fmt::format(
        "{:<13}speed x{:.4f} (1-sigma {:.4f}), yaw rate x{:.4f} (1-sigma {:.4f}) against the "
        "nominal model\n",
        "odometry", s.speed_scale, s.sigma_speed_scale, s.yaw_rate_scale, s.sigma_yaw_rate_scale);
  }
  const GnssNoiseReport& g = gnss_noise;
  if (g.adapted) {
    text += fmt::format(
        "{:<13}residuals {:.3g} m RMS where {:.3g} m was configured: solved again with white "
        "{:.3g} m{}; sigma x{:.2f}\n",
        "gnss noise", g.residual_sigma_m, g.configured_sigma_m, g.white_sigma_m,
        g.gauss_markov_sigma_m > 0.0
            ? fmt::format(" and a correlated {:.3g} m over {:.0f} s (modelled as {:.3g} m over "
                          "{:.0f} s)",
                          g.gauss_markov_sigma_m, g.gauss_markov_tau_s,
                          g.model_gauss_markov_sigma_m, g.model_gauss_markov_tau_s)
        : g.model_gauss_markov_sigma_m > 0.0
            ? fmt::format(" and the stated correlated {:.3g} m over {:.0f} s",
                          g.model_gauss_markov_sigma_m, g.model_gauss_markov_tau_s)
            : std::string(),
        g.sigma_inflation);
    if (g.reverted) {
      text += fmt::format(
          "{:<13}that estimate left the plausible band: the first one stands, its sigma x{:.2f}\n",
          "", g.sigma_inflation);
    }
  } else if (g.residual_sigma_m > 0.0) {
    text += fmt::format("{:<13}residuals {:.3g} m RMS, as configured ({:.3g} m)\n", "gnss noise",
                        g.residual_sigma_m, g.configured_sigma_m);
  }
  if (gentle_limits) {
    text += fmt::format(
        "{:<13}{} of {} keyframe intervals inside the limits feed the odometry ({:.0f} %)\n",
        "gentle", odometry_intervals_used, odometry_intervals,
        100.0 * static_cast<double>(odometry_intervals_used) /
            static_cast<double>(std::max<std::size_t>(odometry_intervals, 1)));
  }
  text += batch::tyre_selection_report(*this);
  if (mounting_detection) text += batch::mounting_detection_report(*mounting_detection);
  if (latency_detection) text += batch::latency_detection_report(*latency_detection, estimate);
  if (reference_circumference) {
    const ReferenceCircumference& r = *reference_circumference;
    text += fmt::format(
        "{:<13}c_RL {:.6f} m (1-sigma {:.3f} mm), c_RR {:.6f} m (1-sigma {:.3f} mm) rolling "
        "straight at a steady {:g} m/s, slip and load included{}\n",
        "rolling", r.circumference_rl_m, 1e3 * r.sigma_rl_m, r.circumference_rr_m,
        1e3 * r.sigma_rr_m, r.speed_mps, r.identified ? "" : ": not identified");
  }
  if (body_sigma_m[0] > 0.0 || body_sigma_m[1] > 0.0) {
    std::vector<std::string> assumed;
    for (const batch::BodyUncertainty& u : batch::kBodyUncertainties) assumed.push_back(u.text());
    // The number worth measuring first: the one whose uncertainty moves the circumferences most.
    const auto largest = std::max_element(
        body_sigma_parts.begin(), body_sigma_parts.end(), [](const auto& a, const auto& b) {
          return std::max(a.sigma_m[0], a.sigma_m[1]) < std::max(b.sigma_m[0], b.sigma_m[1]);
        });
    const std::string most =
        largest == body_sigma_parts.end()
            ? ""
            : fmt::format("; most of it {}'s, {:.3g} / {:.3g} mm", largest->key,
                          1e3 * largest->sigma_m[0], 1e3 * largest->sigma_m[1]);
    text += fmt::format(
        "{:<13}the circumferences' sigma includes {:.3g} / {:.3g} mm from the body's uncertainty "
        "(vehicle.yaml body: {}{})\n",
        "body", 1e3 * body_sigma_m[0], 1e3 * body_sigma_m[1], fmt::join(assumed, ", "), most);
  }
  if (forward_offset_sigma_m[0] > 0.0 || forward_offset_sigma_m[1] > 0.0) {
    text += fmt::format(
        "{:<13}the circumferences' sigma includes {:.3g} / {:.3g} mm from the accelerometer's "
        "forward offset, known to +-{:.3g} m/s^2 (the tyre model takes ax for drive force)\n",
        "imu ax", 1e3 * forward_offset_sigma_m[0], 1e3 * forward_offset_sigma_m[1],
        forward_offset_sigma_mps2);
  }
  if (held_sigma_m[0] > 0.0 || held_sigma_m[1] > 0.0) {
    std::vector<std::string> parts;
    for (const HeldSigmaPart& part : held_sigma_parts) {
      parts.push_back(fmt::format("{} +-{:.2g}: {:.3g} / {:.3g} mm", part.key,
                                  part.coefficient_sigma, 1e3 * part.sigma_m[0],
                                  1e3 * part.sigma_m[1]));
    }
    text += fmt::format(
        "{:<13}the circumferences' sigma includes {:.3g} / {:.3g} mm from the tyre coefficients "
        "held, that this log cannot identify or the car fixes: each where a car's value and the "
        "log's own word put it (a regression term, which no car sizes, at zero with the log's "
        "word for its spread; at zero where its fit wandered or the rear wheels roll free), and "
        "its spread there ({})\n",
        "held", 1e3 * held_sigma_m[0], 1e3 * held_sigma_m[1], fmt::join(parts, ", "));
  }
  if (model_spread_m[0] > 0.0 || model_spread_m[1] > 0.0) {
    text += fmt::format(
        "{:<13}the circumferences' sigma includes {:.3g} / {:.3g} mm, their gap (or the criteria's "
        "share of it) to {}\n",
        "spread", 1e3 * model_spread_m[0], 1e3 * model_spread_m[1],
        !tyre_selection.plain_gap_to.empty()
            ? "a tyre model's fit of this log (the tyre model line names it): the plain "
              "circumferences are the ones this drive rolled on, slip and load in them, not the "
              "ones at rest"
        : tyre_selection.body_in_doubt()
            ? "the regression terms' fit of this log, which needs no body: the physical terms' "
              "circumferences at rest, which rest on vehicle.yaml's body, disagree with it beyond "
              "their combined sigma"
            : "the physical terms' fit of this log: the regression terms extrapolate to rest no "
              "surer than the two models agree");
  }
  if (consistency) text += fmt::format("{:<13}{}\n", "consistency", consistency->verdict);
  text += fmt::format("{:<13}{}\n", "solver", usable() ? message : solver_report);
  return text + report_ending(*this);
}

}  // namespace odocal
