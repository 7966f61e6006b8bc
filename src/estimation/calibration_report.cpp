#include "calibration_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "odocal/model/angle.hpp"
#include "odocal/model/tyre_car_prior.hpp"

namespace odocal {
namespace {

std::string errors_line(const char* label, const DeadReckoningSummary& s) {
  return fmt::format("{:<13}mean {:.3f} m / {:.3f} deg, max {:.3f} m / {:.3f} deg\n", label,
                     s.mean_position_m, deg_from_rad(s.mean_heading_rad), s.max_position_m,
                     deg_from_rad(s.max_heading_rad));
}

std::string estimate_line(const char* name, double estimate, double nominal, double sigma) {
  return fmt::format("{}         {:.6f} m ({:+.3f} mm from nominal, 1-sigma {:.3f} mm)\n", name,
                     estimate, 1e3 * (estimate - nominal), 1e3 * sigma);
}

bool physical_terms_fitted(const TyreModel& model) {
  return std::any_of(kTyreCoefficients.begin(), kTyreCoefficients.end(), [&](const auto& c) {
    return c.terms == TyreTerms::kPhysical && model.*(c.member) != 0.0;
  });
}

}  // namespace

double CalibrationSummary::sigma_rl_m() const { return std::sqrt(std::max(0.0, covariance(0, 0))); }
double CalibrationSummary::sigma_rr_m() const { return std::sqrt(std::max(0.0, covariance(1, 1))); }

bool CalibrationSummary::track_share_worth_naming() const {
  constexpr double kShareWorthNaming = 0.1;
  return track_sigma_m[0] > kShareWorthNaming * sigma_rl_m() ||
         track_sigma_m[1] > kShareWorthNaming * sigma_rr_m();
}

std::string CalibrationSummary::brief_report() const {
  return fmt::format("{}: c_RL {:.6f} m (1-sigma {:.3f} mm), c_RR {:.6f} m (1-sigma {:.3f} mm), {}",
                     method_name(method), estimate.circumference_rl_m, 1e3 * sigma_rl_m(),
                     estimate.circumference_rr_m, 1e3 * sigma_rr_m(),
                     usable()
                         ? enum_name(termination)
                         : fmt::format("not usable ({}): {}", enum_name(termination), message));
}

std::string report_heading(const CalibrationSummary& s) {
  return fmt::format("method       {} ({} reference samples, {:.1f} m, heading from {})\n",
                     method_name(s.method), s.reference_samples, s.distance_m,
                     s.reference_heading_source) +
         estimate_line("c_RL", s.estimate.circumference_rl_m, s.nominal.circumference_rl_m,
                       s.sigma_rl_m()) +
         estimate_line("c_RR", s.estimate.circumference_rr_m, s.nominal.circumference_rr_m,
                       s.sigma_rr_m());
}

std::string report_ending(const CalibrationSummary& s) {
  std::string text;
  if (!s.model_adequacy.verdict.empty())
    text += fmt::format("{:<13}{}\n", "model", s.model_adequacy.verdict);
  if (s.misfit_sigma_scale > 1.0) {
    text += fmt::format(
        "{:<13}the odometry residuals are {:.3g} times as wide as their noise model (chi2/dof "
        "{:.3g} over {} intervals): every sigma widened x{:.3g}\n",
        "misfit", s.misfit_sigma_scale, s.model_adequacy.chi2_per_dof, s.model_adequacy.intervals,
        s.misfit_sigma_scale);
  }
  if (s.track_under_prior) {
    text += fmt::format(
        "{:<13}fitted under its prior, vehicle.yaml's track_width_m +-{:.3g} % (the two-wheel "
        "model explains this log: no load transfer seen to move it), to {:.4f} m; it shares "
        "{:.3g} / {:.3g} mm of the circumferences' sigma\n",
        "track", 100.0 * s.track_width_uncertainty, s.estimate.track_width_m,
        1e3 * s.track_sigma_m[0], 1e3 * s.track_sigma_m[1]);
  } else if (std::isfinite(s.judged_track_m)) {
    text += fmt::format(
        "{:<13}held at vehicle.yaml's {:.4f} m; the judge's plain fit, the track under its prior "
        "(+-{:.3g} %: the two-wheel model explains this log), puts it at {:.4f} m (1-sigma "
        "{:.2g} m): the circumferences' sigma includes {:.3g} / {:.3g} mm for the held track's "
        "distance from it\n",
        "track", s.estimate.track_width_m, 100.0 * s.track_width_uncertainty, s.judged_track_m,
        s.judged_track_sigma_m, 1e3 * s.track_sigma_m[0], 1e3 * s.track_sigma_m[1]);
  } else if (s.track_share_worth_naming()) {
    text += fmt::format(
        "{:<13}the circumferences' sigma includes {:.3g} / {:.3g} mm from the track width held: "
        "the track the wheels roll on may lie +-{:.3g} % from vehicle.yaml's (load moves it), "
        "and a turn's wheel-speed difference over its yaw rate is the track over the "
        "circumference\n",
        "track", 1e3 * s.track_sigma_m[0], 1e3 * s.track_sigma_m[1],
        100.0 * s.track_width_uncertainty);
  }
  // A passenger tyre's centrifugal growth at the drive's distance-weighted mean v^2: in the plain
  // model's circumferences (they are the ones the drive rolled on), and left out of the physical
  // terms' at rest, which extrapolate with a radius that does not grow (independent drives with
  // growth, slip and load: 2.2 mm off at a sigma of 0.31 mm; docs/tyre-model.md). Named where it
  // is more than half the circumferences' sigma.
  const double v2 = s.coverage.mean_square_speed_m2ps2();
  const double growth_m = kCarGrowthPerSpeedSquaredS2pm2 * v2 * 0.5 *
                          (s.estimate.circumference_rl_m + s.estimate.circumference_rr_m);
  const double sigma_m = std::max(s.sigma_rl_m(), s.sigma_rr_m());
  const bool growth_matters = s.usable() && growth_m > 0.5 * sigma_m;
  // What a constant per wheel is, so that it is not read as the tyre at rest: a residual test
  // cannot see a slip that is the same all drive long (docs/tyre-model.md).
  if (s.usable() && s.tyre_model.plain()) {
    const std::string growth =
        growth_matters
            ? fmt::format(
                  "; a passenger tyre's centrifugal growth (about {:.2g} per (m/s)^2) at this "
                  "drive's distance-weighted mean v^2 of {:.0f} (m/s)^2 is in them too, some "
                  "{:.2g} mm above the circumferences at a garage's speeds",
                  kCarGrowthPerSpeedSquaredS2pm2, v2, 1e3 * growth_m)
            : "";
    text += fmt::format(
        "{:<13}the circumferences this drive rolled on, its average slip and load in them: at "
        "rest a driven axle's are larger by its slip at cruise (about 1.6 per mille at 10 m/s); "
        "the batch's tyre_model: physical separates the two{}\n",
        "rolling", growth);
  }
  if (growth_matters && physical_terms_fitted(s.tyre_model)) {
    text += fmt::format(
        "{:<13}not in the tyre terms: a passenger tyre's radius grows with speed (centrifugal, "
        "about {:.2g} per (m/s)^2), which at this drive's distance-weighted mean v^2 of {:.0f} "
        "(m/s)^2 would put the circumferences at rest {:.2g} mm below these ({:.2g} times their "
        "sigma, which leaves it out); for a garage's speeds, calibrate on a slow drive or check "
        "with `validate` on one\n",
        "growth", kCarGrowthPerSpeedSquaredS2pm2, v2, 1e3 * growth_m, growth_m / sigma_m);
  }
  if (const std::string prepared = s.preparation.describe(); !prepared.empty())
    text += fmt::format("{:<13}{}\n", "log", prepared);
  text += "dead reckoning of the whole log against the reference:\n";
  text += errors_line("  before", s.before);
  text += errors_line("  after", s.after);
  if (s.accelerometer_walk.heading_rad > 0.0) {
    const bool given = s.accelerometer_walk.forward_force_given;
    text += fmt::format(
        "  {:<11}the tyre model takes each sample's {} from the accelerometer: its noise "
        "({:.3g} / {:.3g} m/s^2 forward / left per sample) alone walks this heading by {:.3g} deg "
        "(1-sigma at the log's end)\n",
        "noise", given ? "lateral force (the forward one from drive_force_n)" : "force",
        s.accelerometer_walk.noise_x_mps2, s.accelerometer_walk.noise_y_mps2,
        deg_from_rad(s.accelerometer_walk.heading_rad));
  }
  if (s.usable() && !s.note.empty()) text += fmt::format("{:<13}{}\n", "note", s.note);
  text += s.usable() ? fmt::format("{:<13}usable ({})\n", "outcome", enum_name(s.termination))
                     : fmt::format("{:<13}NOT USABLE ({}): {}\n", "outcome",
                                   enum_name(s.termination), s.message);
  return text;
}

}  // namespace odocal
