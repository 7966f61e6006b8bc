#include "odocal/estimation/model_adequacy.hpp"

#include <fmt/format.h>

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <optional>

namespace odocal {
namespace {

// The correlation of y and x once both are cleared of a constant and the controls (least
// squares): what x explains of y beyond what the controls already could.
double partial_correlation(const std::vector<double>& y, const std::vector<double>& x,
                           const std::vector<const std::vector<double>*>& controls) {
  const auto n = static_cast<Eigen::Index>(y.size());
  Eigen::MatrixXd Z(n, 1 + static_cast<Eigen::Index>(controls.size()));
  Eigen::VectorXd yv(n), xv(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    Z(i, 0) = 1.0;
    for (std::size_t c = 0; c < controls.size(); ++c)
      Z(i, static_cast<Eigen::Index>(c) + 1) = (*controls[c])[k];
    yv(i) = y[k];
    xv(i) = x[k];
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Z);
  const Eigen::VectorXd ry = yv - Z * qr.solve(yv);
  const Eigen::VectorXd rx = xv - Z * qr.solve(xv);
  const double denominator = std::sqrt(ry.squaredNorm() * rx.squaredNorm());
  return denominator > 0.0 ? ry.dot(rx) / denominator : 0.0;
}

std::vector<double> rows_where(const std::vector<double>& values, const std::vector<bool>& keep) {
  std::vector<double> kept;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (keep[i]) kept.push_back(values[i]);
  }
  return kept;
}

// What a dependence says about the tyre, in the verdict.
std::string likely_cause(const ResidualDependence& d) {
  if (d.quantity == "lateral acceleration")
    return "the rolling radius changes with load (load transfer in turns)";
  if (d.quantity == "longitudinal acceleration" && d.residual == "Doppler speed")
    return "the wheels slip or roll on a radius that the load moves (drive and brake slip, "
           "longitudinal load transfer), or the Doppler speed and the wheels are not simultaneous "
           "(a receiver's velocity filter, a wheel-speed latency: estimate_latency)";
  if (d.quantity == "longitudinal acceleration")
    return "the driven or braked wheels slip (drive and brake slip), or the wheel speeds lag the "
           "other sensors (a latency makes an along-track error of -latency x a_x)";
  if (d.quantity == "curvature")
    return "the track width is off, or the rolling radius changes in turns (estimate_track_width "
           "tells which)";
  if (d.quantity == "grade")
    return "the driven wheels slip with the force that climbing takes (drive slip uphill, "
           "engine braking downhill)";
  return "the rolling radius grows with speed";
}

}  // namespace

double misfit_sigma_scale(const ModelAdequacy& adequacy) {
  return adequacy.judged && adequacy.chi2_per_dof > 1.0 ? std::sqrt(adequacy.chi2_per_dof) : 1.0;
}

ModelAdequacy assess_model_adequacy(const std::vector<OdometryResidualSample>& samples,
                                    const std::string& tyre_terms, double min_distance_m,
                                    double min_correlation, double min_t) {
  ModelAdequacy result;
  // The driving state of each interval from the fitted poses: speed, yaw rate, and the
  // longitudinal acceleration from the neighbouring intervals' speeds.
  std::vector<double> speed(samples.size()), distance(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const OdometryResidualSample& s = samples[i];
    distance[i] = (s.pose1.head<2>() - s.pose0.head<2>()).norm();
    speed[i] = distance[i] / std::max(s.t1_s - s.t0_s, 1e-9);
  }
  std::vector<double> heading_per_m, along_per_m, lateral, longitudinal, speed_squared, curvature;
  std::vector<double> whitened_heading, grade, doppler_per_m;
  double chi2 = 0.0;
  for (std::size_t i = 1; i + 1 < samples.size(); ++i) {
    const OdometryResidualSample& s = samples[i];
    if (distance[i] < min_distance_m) continue;
    const double dt = s.t1_s - s.t0_s;
    const double mid_prev = 0.5 * (samples[i - 1].t0_s + samples[i - 1].t1_s);
    const double mid_next = 0.5 * (samples[i + 1].t0_s + samples[i + 1].t1_s);
    heading_per_m.push_back(s.error(2) / distance[i]);
    along_per_m.push_back(s.error(0) / distance[i]);
    lateral.push_back(speed[i] * (s.pose1(2) - s.pose0(2)) / dt);
    curvature.push_back((s.pose1(2) - s.pose0(2)) / distance[i]);
    longitudinal.push_back((speed[i + 1] - speed[i - 1]) / std::max(mid_next - mid_prev, 1e-9));
    speed_squared.push_back(speed[i] * speed[i]);
    whitened_heading.push_back(s.whitened(2));
    grade.push_back(s.grade);
    doppler_per_m.push_back(s.doppler_error_m / distance[i]);
    chi2 += s.whitened.squaredNorm();
  }
  result.intervals = heading_per_m.size();
  if (result.intervals < 10) {
    result.verdict = "too few moving keyframe intervals to judge the model";
    return result;
  }
  result.judged = true;
  const auto n = static_cast<double>(result.intervals);
  result.chi2_per_dof = chi2 / (3.0 * n);
  double lag = 0.0, zero = 0.0;
  for (std::size_t i = 0; i < whitened_heading.size(); ++i) {
    zero += whitened_heading[i] * whitened_heading[i];
    if (i > 0) lag += whitened_heading[i] * whitened_heading[i - 1];
  }
  result.autocorrelation = zero > 0.0 ? lag / zero : 0.0;

  // The heading error per metre against lateral acceleration (load) and against curvature (a
  // track that is off, which at one speed looks the same: both are reported). Along-track:
  // acceleration beyond what speed explains, and speed beyond acceleration.
  const auto test = [&](const char* residual, const std::vector<double>& r, const char* quantity,
                        const std::vector<double>& q,
                        const std::vector<const std::vector<double>*>& controls) {
    const double rho = partial_correlation(r, q, controls);
    const double dof = static_cast<double>(r.size()) - 2.0 - static_cast<double>(controls.size());
    const double t = std::abs(rho) * std::sqrt(dof / std::max(1.0 - rho * rho, 1e-12));
    result.dependences.push_back({residual, quantity, rho, t});
  };
  test("heading", heading_per_m, "lateral acceleration", lateral, {});
  test("heading", heading_per_m, "curvature", curvature, {});
  test("along-track", along_per_m, "longitudinal acceleration", longitudinal, {&speed_squared});
  test("along-track", along_per_m, "speed squared", speed_squared, {&longitudinal});
  // The rows where `known` is finite, of it and of the driving state, when there are enough.
  struct KnownRows {
    std::vector<bool> keep;
    std::vector<double> values, longitudinal, speed_squared;
  };
  const auto rows_known = [&](const std::vector<double>& known) -> std::optional<KnownRows> {
    std::vector<bool> keep(known.size());
    std::transform(known.begin(), known.end(), keep.begin(),
                   [](double v) { return std::isfinite(v); });
    if (std::count(keep.begin(), keep.end(), true) < 10) return std::nullopt;
    return KnownRows{keep, rows_where(known, keep), rows_where(longitudinal, keep),
                     rows_where(speed_squared, keep)};
  };
  // Climbing takes a drive force that the horizontal acceleration does not show (m g grade):
  // slip beyond what acceleration and speed explain. Only where the grade is known (a block of a
  // long log without altitude has none).
  if (const auto graded = rows_known(grade)) {
    test("along-track", rows_where(along_per_m, graded->keep), "grade", graded->values,
         {&graded->longitudinal, &graded->speed_squared});
  }
  // The Doppler speed against the wheels: the slip that the poses, following the wheels between
  // fixes, keep only a sliver of in the along-track residual.
  if (const auto doppler = rows_known(doppler_per_m)) {
    test("Doppler speed", doppler->values, "longitudinal acceleration", doppler->longitudinal,
         {&doppler->speed_squared});
    test("Doppler speed", doppler->values, "speed squared", doppler->speed_squared,
         {&doppler->longitudinal});
  }

  const ResidualDependence* strongest = nullptr;
  for (const ResidualDependence& d : result.dependences) {
    if (!d.counts(min_correlation, min_t)) continue;
    if (strongest == nullptr || std::abs(d.correlation) > std::abs(strongest->correlation))
      strongest = &d;
  }
  // With tyre terms fitted these are their residuals: a verdict on "the two-wheel model" would
  // describe a model that was not the one judged.
  const std::string model =
      tyre_terms.empty() ? "the two-wheel model"
                         : fmt::format("the two-wheel model with the {} tyre terms", tyre_terms);
  if (strongest == nullptr) {
    result.verdict = fmt::format(
        "{} explains this log: its odometry residuals follow neither acceleration nor speed "
        "(|rho| < {:.1f} over {} intervals; chi2/dof {:.2f})",
        model, min_correlation, result.intervals, result.chi2_per_dof);
    result.explains = true;
    return result;
  }
  const std::string consequence = tyre_terms.empty()
                                      ? "a constant circumference per wheel cannot express that"
                                      : "the tyre terms leave that in the residuals";
  result.verdict = fmt::format(
      "{} does not explain this log: the {} residual follows {} (rho = {:.2f} over {} "
      "intervals): {}; {}, so dead reckoning drifts where the driving differs from this log's "
      "average",
      model, strongest->residual, strongest->quantity, strongest->correlation, result.intervals,
      likely_cause(*strongest), consequence);
  return result;
}

}  // namespace odocal
