// A solved batch problem turned into the BatchSummary: every parameter with its sigma and
// verdict, the rolling circumference, the model adequacy, and whether the result is usable.
#include <ceres/ceres.h>
#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include "batch_body_uncertainty.hpp"
#include "batch_covariance.hpp"
#include "batch_observability.hpp"
#include "batch_refusal.hpp"
#include "batch_solve_steps.hpp"
#include "calibration_report.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/model/tyre_car_prior.hpp"

namespace odocal::batch {
namespace {

// Each rear wheel's effective circumference rolling straight at a steady `speed`: c_i times the
// tyre model's factor there, its sigma from the data's covariance (`covariance`, the parameters')
// and from the body's responses, each the parameters' move and the factor's own change with the
// body number (the rolling resistance's slip at constant speed is in the factor, so a body number
// moves both c_i and the factor).
ReferenceCircumference reference_circumference(
    const BatchProblem& batch, const ParamsBlock& p,
    const Eigen::Matrix<double, batch::kParams, batch::kParams>& covariance, double speed,
    double max_sigma) {
  DrivingState steady;
  steady.speed_mps = static_cast<float>(speed);
  const batch::ParamsVector at = Eigen::Map<const batch::ParamsVector>(p.data());
  const auto rolling = [&](const batch::ParamsVector& params, const VehicleBody& body, int wheel) {
    const TyreModel model = TyreModel::from(params.tail<TyreModel::kCoefficients>());
    return params(wheel) *
           tyre_factor(model, steady, wheel == 0 ? RearWheel::kLeft : RearWheel::kRight, body);
  };
  ReferenceCircumference r;
  r.speed_mps = speed;
  r.identified = true;
  for (int wheel = 0; wheel < 2; ++wheel) {
    const double value = rolling(at, batch.body(), wheel);
    batch::ParamsVector gradient = batch::ParamsVector::Zero();
    for (int j = 0; j < batch::kParams; ++j) {
      batch::ParamsVector moved = at;
      const double step = 1e-7 * std::max(1.0, std::abs(at(j)));
      moved(j) += step;
      gradient(j) = (rolling(moved, batch.body(), wheel) - value) / step;
    }
    double variance = gradient.dot(covariance * gradient);
    const auto add_response = [&](const BatchProblem::Response& response) {
      const double change =
          (rolling(at + response.moved, response.body, wheel) - value) / response.step;
      variance += change * change;
    };
    for (const BatchProblem::Response& response : batch.body_responses()) add_response(response);
    for (const BatchProblem::HeldResponse& held : batch.held_responses())
      add_response(held.response);
    if (const auto& offset = batch.forward_offset_response()) add_response(*offset);
    const double sigma = std::sqrt(std::max(variance, 0.0));
    (wheel == 0 ? r.circumference_rl_m : r.circumference_rr_m) = value;
    (wheel == 0 ? r.sigma_rl_m : r.sigma_rr_m) = sigma;
    r.identified = r.identified && std::isfinite(sigma) && sigma <= max_sigma;
  }
  return r;
}

// Why a circumference is not identified where most of its sigma is the held track's: the turns,
// not the GNSS fixes, set its scale.
std::string track_verdict(const BatchSummary& summary, std::size_t wheel, double sigma_m) {
  const double track_m = summary.track_sigma_m[wheel];
  return fmt::format(
      "the turns, not the GNSS fixes, set its scale here, through the track width {} (of its "
      "1-sigma, {:.2g} mm from the track the wheels roll on, vehicle.yaml's track_width_m "
      "+-{:.2g} %: load moves it; {:.2g} mm from the rest): drive more distance under open sky, "
      "or set estimate_track_width",
      summary.track_under_prior ? "under its prior" : "held", 1e3 * track_m,
      100.0 * summary.track_width_uncertainty,
      1e3 * std::sqrt(std::max(0.0, sigma_m * sigma_m - track_m * track_m)));
}

// Why a circumference beside a tyre model is not identified: at rest it is an extrapolation from
// the states driven, and its sigma carries the log's own noise, what the log cannot identify (the
// body's numbers, the held coefficients) and the two models' gap. Every share is named, largest
// first, with what would shrink it, so that the user states or drives what matters most.
std::string extrapolation_verdict(const BatchSummary& summary, std::size_t wheel, double sigma_m,
                                  double spread_m, bool has_doppler) {
  struct Share {
    double size_m;
    std::string text, advice;
  };
  std::vector<Share> shares;
  // A share with parts: its total, and the part that moves the circumference most, which `act`
  // on names.
  const auto add_parts = [&](double total_m, const auto& parts, const char* from, auto act) {
    const auto largest = std::max_element(
        parts.begin(), parts.end(),
        [wheel](const auto& a, const auto& b) { return a.sigma_m[wheel] < b.sigma_m[wheel]; });
    if (!(total_m > 0.0) || largest == parts.end()) return;
    shares.push_back({total_m,
                      fmt::format("{:.2g} mm {}, {:.2g} mm of it from {}", 1e3 * total_m, from,
                                  1e3 * largest->sigma_m[wheel], largest->key),
                      act(largest->key)});
  };
  add_parts(summary.body_sigma_m[wheel], summary.body_sigma_parts, "from the body's uncertainty",
            [](const std::string&) { return std::string("state vehicle.yaml's body"); });
  add_parts(summary.held_sigma_m[wheel], summary.held_sigma_parts,
            "from the tyre coefficients held",
            [](const std::string& key) { return "drive more of what shows " + key; });
  if (const double offset_m = summary.forward_offset_sigma_m[wheel]; offset_m > 0.0) {
    shares.push_back(
        {offset_m,
         fmt::format("{:.2g} mm from the accelerometer's forward offset (+-{:.2g} m/s^2)",
                     1e3 * offset_m, summary.forward_offset_sigma_mps2),
         "level the IMU and stop the car a few times in the log, so that its offset is measured"});
  }
  if (spread_m > 0.0) {
    // The physical terms carry their gap to the regression terms only where a body number is
    // likely wrong (witness_physical_fit).
    const bool to_regression = summary.tyre_selection.body_in_doubt();
    shares.push_back({spread_m,
                      fmt::format("{:.2g} mm from the gap to where the {} terms' fit puts it",
                                  1e3 * spread_m, to_regression ? "regression" : "physical"),
                      to_regression ? "check vehicle.yaml's body" : "drive more gently"});
  }
  double named_variance = 0.0;
  for (const Share& share : shares) named_variance += share.size_m * share.size_m;
  if (std::isfinite(sigma_m)) {
    const double own_m = std::sqrt(std::max(0.0, sigma_m * sigma_m - named_variance));
    const double misfit = summary.misfit_sigma_scale;
    shares.push_back(
        {own_m,
         misfit > 1.0 ? fmt::format("{:.2g} mm from the log's own noise, widened {:.2g} times by "
                                    "the model's misfit (chi2/dof {:.3g})",
                                    1e3 * own_m, misfit, summary.model_adequacy.chi2_per_dof)
                      : fmt::format("{:.2g} mm from the log's own noise", 1e3 * own_m),
         has_doppler ? "drive longer and more gently"
                     : "drive longer and more gently, or log the GNSS receiver's Doppler speed "
                       "(gnss.csv speed_mps)"});
  }
  std::stable_sort(shares.begin(), shares.end(),
                   [](const Share& a, const Share& b) { return a.size_m > b.size_m; });
  std::vector<std::string> texts, advice;
  for (const Share& share : shares) {
    texts.push_back(share.text);
    if (std::find(advice.begin(), advice.end(), share.advice) == advice.end())
      advice.push_back(share.advice);
  }
  const std::string extrapolation =
      "with the tyre model the circumference at rest is an extrapolation from this drive's slip "
      "and load";
  if (texts.empty()) return extrapolation + " (drive longer and more gently)";
  return fmt::format("{} (of its 1-sigma, {}: {})", extrapolation, fmt::join(texts, "; "),
                     fmt::join(advice, "; "));
}

// A plain circumference whose sigma carries its gap to a tyre model's fit (tyre_model none chosen
// by hand, judged: tyre_model_judge.cpp; or a model that is no tyre fits the log decisively
// better: tyre_model_selection.cpp). Under none, auto is the advice; under auto the model line
// says what is wrong.
std::string plain_gap_verdict(double sigma_m, double gap_m, TyreModelChoice configured) {
  return fmt::format(
      "the plain model's circumference is the one this drive rolled on, slip and load in it: a "
      "tyre model, which fits this log as well or better, puts the circumference at rest "
      "elsewhere (of its 1-sigma, {:.3g} mm from that gap, or the share of it that the criteria "
      "weigh; {:.2g} mm from the log's own noise); {}",
      1e3 * gap_m, 1e3 * std::sqrt(std::max(0.0, sigma_m * sigma_m - gap_m * gap_m)),
      configured == TyreModelChoice::kNone ? "use tyre_model: auto" : "see the model line");
}

// A circumference that only the misfit's widening leaves unidentified.
std::string misfit_verdict(const BatchSummary& summary) {
  return fmt::format(
      "the model does not fit this log: its odometry residuals are {:.2g} times as wide as their "
      "noise (chi2/dof {:.3g}), and so is every sigma (the model line says what they follow; "
      "drive more gently, or choose a tyre_model that explains the log)",
      summary.misfit_sigma_scale, summary.model_adequacy.chi2_per_dof);
}

}  // namespace

void summarise(const Log& log, const BatchOptions& b, BatchProblem& batch,
               const ceres::Solver::Summary& solver, BatchSummary& summary) {
  const auto& p = batch.params();
  summary.estimate = {p[0], p[1], p[2]};
  // An adapted noise that ran away and whose widening could not be measured leaves no sigma.
  const auto uncertainty =
      std::isfinite(summary.gnss_noise.covariance_scale) ? batch.uncertainty() : std::nullopt;
  const double inf = std::numeric_limits<double>::infinity();
  const auto sigma = [&](double variance) { return uncertainty ? std::sqrt(variance) : inf; };
  BatchProblem::Uncertainty u = uncertainty.value_or(BatchProblem::Uncertainty{});
  summary.model_adequacy = assess_model_adequacy(batch.odometry_errors(),
                                                 batch.tyre_fitted() && !batch.tyre_model().plain()
                                                     ? tyre_model_option(*batch.tyre_terms())
                                                     : "");
  summary.misfit_sigma_scale = misfit_sigma_scale(summary.model_adequacy);
  const bool mounting_open =
      !b.estimate_lever_arm || (!b.estimate_heading_bias && log.heading.has_value());
  summary.mounting_residuals =
      b.detect_mounting && mounting_open ? batch.mounting_residuals() : MountingResiduals{};
  const double scale =
      summary.gnss_noise.covariance_scale * summary.misfit_sigma_scale * summary.misfit_sigma_scale;
  u.params *= scale;
  u.lever *= scale;
  u.gyro_bias *= scale;
  u.heading_bias *= scale;
  u.latency *= scale;
  // The data's own covariance, before the body's and the models' spread: a circumference rolling
  // at a reference speed adds the body's share per body number itself, and makes no
  // extrapolation to rest.
  const Eigen::Matrix<double, batch::kParams, batch::kParams> data_covariance = u.params;
  u.params += batch.body_covariance() + batch.held_covariance() +
              batch.forward_offset_covariance() + batch.track_covariance();
  const std::array<double, 2>& spread = batch.model_spread_m();
  for (int w = 0; w < 2; ++w)
    u.params(w, w) += spread[static_cast<std::size_t>(w)] * spread[static_cast<std::size_t>(w)];
  summary.model_spread_m = spread;
  summary.body_sigma_m = {std::sqrt(batch.body_covariance()(0, 0)),
                          std::sqrt(batch.body_covariance()(1, 1))};
  const auto moved_circumferences = [](const BatchProblem::Response& response) {
    return std::array<double, 2>{std::abs(response.moved(0)) / response.step,
                                 std::abs(response.moved(1)) / response.step};
  };
  summary.body_sigma_parts.clear();
  for (std::size_t i = 0; i < batch.body_responses().size(); ++i) {
    summary.body_sigma_parts.push_back(
        {kBodyUncertainties[i].key, moved_circumferences(batch.body_responses()[i])});
  }
  summary.held_sigma_m = {std::sqrt(batch.held_covariance()(0, 0)),
                          std::sqrt(batch.held_covariance()(1, 1))};
  summary.forward_offset_sigma_m = {std::sqrt(batch.forward_offset_covariance()(0, 0)),
                                    std::sqrt(batch.forward_offset_covariance()(1, 1))};
  summary.forward_offset_sigma_mps2 =
      batch.forward_offset_response() ? batch.forward_offset_sigma() : 0.0;
  summary.track_under_prior = batch.track_prior_sigma_m() > 0.0;
  if (summary.track_under_prior) {
    const auto shared = [&](Eigen::Index w) {
      return u.params(2, 2) > 0.0 ? std::abs(u.params(w, 2)) / std::sqrt(u.params(2, 2)) : 0.0;
    };
    summary.track_sigma_m = {shared(0), shared(1)};
  } else {
    summary.track_sigma_m = {std::sqrt(batch.track_covariance()(0, 0)),
                             std::sqrt(batch.track_covariance()(1, 1))};
  }
  const bool track_considered = summary.track_sigma_m[0] > 0.0 || summary.track_sigma_m[1] > 0.0;
  summary.track_width_uncertainty = track_considered ? b.track_width_uncertainty : 0.0;
  summary.held_sigma_parts.clear();
  for (const BatchProblem::HeldResponse& held : batch.held_responses()) {
    const auto j = static_cast<std::size_t>(held.coefficient);
    summary.held_sigma_parts.push_back(
        {tyre_parameter_name(kTyreCoefficients[j]), moved_circumferences(held.response),
         held.response.moved(kTyreOffset + held.coefficient) / held.response.step});
  }
  summary.parameters = {
      {"circumference_rl_m", p[0], sigma(u.params(0, 0)), true, true, ""},
      {"circumference_rr_m", p[1], sigma(u.params(1, 1)), true, true, ""},
      {"track_width_m", p[2], sigma(u.params(2, 2)),
       b.estimate_track_width || summary.track_under_prior, true, ""},
      {"gyro_bias_radps", batch.gyro_bias(), sigma(u.gyro_bias), b.estimate_gyro_bias, true, ""},
      {"heading_bias_rad", batch.heading_bias(), sigma(u.heading_bias), b.estimate_heading_bias,
       true, ""},
      {"lever_arm_x_m", batch.lever()[0], sigma(u.lever(0, 0)), b.estimate_lever_arm, true, ""},
      {"lever_arm_y_m", batch.lever()[1], sigma(u.lever(1, 1)), b.estimate_lever_arm, true, ""},
      {"latency_s", batch.latency(), sigma(u.latency), b.estimate_latency, true, ""}};
  std::vector<double> thresholds{b.max_sigma_circumference_m,  b.max_sigma_circumference_m,
                                 b.max_sigma_track_width_m,    b.max_sigma_gyro_bias_radps,
                                 b.max_sigma_heading_bias_rad, b.max_sigma_lever_arm_m,
                                 b.max_sigma_lever_arm_m,      b.max_sigma_latency_s};
  const LogCoverage coverage = log_coverage(log, summary.coverage);
  std::vector<bool> block_used{
      true, true, true, log.imu.has_value() && b.use_gyro, log.heading.has_value() && b.use_heading,
      true, true, true};
  for (int j = 0; j < TyreModel::kCoefficients; ++j) {
    const int p_index = kTyreOffset + j;
    const double sigma_j = batch.tyre_fixed_by_car(j) ? batch.car_coefficient(j).sigma
                           : batch.tyre_held(j)       ? batch.tyre_held_sigma(j)
                                                      : sigma(u.params(p_index, p_index));
    summary.parameters.push_back(
        {tyre_parameter_name(kTyreCoefficients[static_cast<std::size_t>(j)]), p[p_index], sigma_j,
         batch.tyre_in_fit(j), true, ""});
    const double rms = batch.regressor_rms()(j);
    thresholds.push_back(rms > 0.0 ? b.max_sigma_tyre_effect / rms : 0.0);
    block_used.push_back(rms > 0.0);
  }
  if (batch.tyre_fitted()) summary.tyre_model = batch.tyre_model();
  std::vector<std::string> problems;
  for (std::size_t i = 0; i < summary.parameters.size(); ++i) {
    EstimatedParameter& parameter = summary.parameters[i];
    if (!parameter.estimated) {
      parameter.sigma = 0.0;
      continue;
    }
    const int coefficient = static_cast<int>(i) - 8;
    if (i >= 8 && batch.tyre_fixed_by_car(coefficient)) {  // the car's, not the log's to identify
      parameter.verdict =
          "held at zero: the rear wheels roll free (vehicle.yaml body.drivetrain: "
          "front), its spread the model's slop";
      continue;
    }
    // A held coefficient is one that the log did not identify, however narrow its sigma then
    // (held with others, where the side slip that widened it was held after it).
    const bool held_for_spread =
        i >= 8 && batch.tyre_held(coefficient) && !batch.tyre_held_below_zero(coefficient);
    parameter.identified = std::isfinite(parameter.sigma) && parameter.sigma <= thresholds[i] &&
                           block_used[i] && !held_for_spread;
    const bool below_zero = i >= 8 && batch.tyre_held_below_zero(coefficient);
    const std::string sign_hold =
        below_zero ? fmt::format(
                         "held at {:.3g}, above zero: the log put it at {:.3g}, below zero within "
                         "its noise, where no driven or braked tyre slips",
                         batch.tyre_held_value(coefficient), batch.tyre_held_estimate(coefficient))
                   : "";
    if (below_zero && parameter.identified) parameter.verdict = sign_hold;
    if (!parameter.identified) {
      parameter.verdict = unidentified_reason(parameter.name, coverage, block_used[i]);
      const bool considered =
          i < 2 && (summary.body_sigma_m[i] > 0.0 || summary.held_sigma_m[i] > 0.0 ||
                    summary.forward_offset_sigma_m[i] > 0.0);  // the held track's: track_verdict
      const bool extrapolated =
          i < 2 && batch.tyre_fitted() && (!batch.tyre_model().plain() || considered);
      if (extrapolated) {
        parameter.verdict = extrapolation_verdict(summary, i, parameter.sigma, spread[i],
                                                  batch.speed_intervals() > 0);
      } else if (i < 2 && spread[i] > 0.0) {
        parameter.verdict = plain_gap_verdict(parameter.sigma, spread[i], b.tyre_model);
      } else if (const double track_m = i < 2 ? summary.track_sigma_m[i] : 0.0;
                 2.0 * track_m * track_m > parameter.sigma * parameter.sigma) {
        parameter.verdict = track_verdict(summary, i, parameter.sigma);
      }
      const double misfit = summary.misfit_sigma_scale;
      if (i < 2 && misfit > 1.0) {
        const auto k = static_cast<Eigen::Index>(i);
        const double widened = data_covariance(k, k) * (1.0 - 1.0 / (misfit * misfit));
        // Identified but for the misfit's widening: that is the reason, not the log's coverage.
        if (parameter.sigma * parameter.sigma - widened <= thresholds[i] * thresholds[i]) {
          parameter.verdict = misfit_verdict(summary);
        } else if (!extrapolated) {
          parameter.verdict += fmt::format(
              "; and its sigma is widened {:.2g} times by the model's misfit (chi2/dof {:.3g})",
              misfit, summary.model_adequacy.chi2_per_dof);
        }
      }
      if (below_zero) {
        parameter.verdict = sign_hold + "; and " + parameter.verdict;
      } else if (i >= 8 && batch.tyre_held(coefficient)) {
        const double held = batch.tyre_held_value(coefficient);
        parameter.verdict = (held == 0.0 ? std::string("held at zero: ")
                                         : fmt::format("held at a car's value, {:.3g}: ", held)) +
                            parameter.verdict;
      }
      problems.push_back(parameter.name + ": " + parameter.verdict);
    }
  }
  summary.covariance = u.params.topLeftCorner<2, 2>();
  summary.params_covariance =
      uncertainty ? u.params.topLeftCorner<3, 3>().eval() : Eigen::Matrix3d::Constant(inf);
  if (b.estimate_track_width && uncertainty) {
    summary.odometry_scales =
        odometry_scales(log.vehicle.nominal_params(), summary.estimate, summary.params_covariance);
  }
  if (uncertainty) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(summary.covariance);
    summary.condition_number =
        std::sqrt(eigen.eigenvalues()(1) / std::max(eigen.eigenvalues()(0), 1e-300));
  } else {
    summary.condition_number = inf;
    summary.covariance.setConstant(inf);
    problems.insert(problems.begin(), kRankDeficientReason);
  }
  summary.identifiability = problems.empty()
                                ? "every requested parameter identified"
                                : fmt::format("not identified: {}", fmt::join(problems, "; "));
  if (!batch.tyre_fitted()) suggest_tyre_model(summary.model_adequacy);
  summary.solver_report = solver.BriefReport();
  summary.gentle_limits = b.gentle_max_speed_mps > 0.0 || b.gentle_max_longitudinal_mps2 > 0.0 ||
                          b.gentle_max_lateral_mps2 > 0.0;
  std::tie(summary.odometry_intervals_used, summary.odometry_intervals) = batch.gentle_intervals();
  summary.keyframes = batch.keyframes();
  summary.gnss_fixes = batch.gnss_residuals();
  summary.doppler_intervals = batch.speed_intervals();

  const std::string doppler =
      summary.doppler_intervals == 0 ? ""
      : summary.doppler_sigma_scale > 1.0
          ? fmt::format(
                " and the Doppler speed over {} intervals (its noise {:.2g} times the "
                "configured, as its residuals show)",
                summary.doppler_intervals, summary.doppler_sigma_scale)
          : fmt::format(" and the Doppler speed over {} intervals", summary.doppler_intervals);
  const std::string solved =
      fmt::format("batch maximum likelihood over {} keyframes and {} GNSS fixes{}; {} solve(s); {}",
                  summary.keyframes, summary.gnss_fixes, doppler, summary.solves,
                  ceres::TerminationTypeToString(solver.termination_type));
  if (batch.tyre_fitted() && !batch.tyre_model().plain() && uncertainty) {
    summary.reference_circumference = reference_circumference(
        batch, p, data_covariance, b.reference_speed_mps, b.max_sigma_circumference_m);
  }
  const bool circumferences_identified =
      uncertainty && summary.parameters[0].identified && summary.parameters[1].identified;
  if (solver.termination_type == ceres::NO_CONVERGENCE) {
    summary.termination = Termination::kNoConvergence;
    summary.message =
        fmt::format("{}: the solver reached max_solver_iterations ({}) before converging", solved,
                    b.max_solver_iterations);
  } else if (!solver.IsSolutionUsable()) {
    summary.termination = Termination::kFailure;
    // Ceres' message can span lines and name memory addresses; its first line says what failed.
    summary.message =
        fmt::format("{}: {}", solved, solver.message.substr(0, solver.message.find('\n')));
  } else if (!circumferences_identified) {
    summary.termination = Termination::kNotIdentifiable;
    summary.message =
        fmt::format("{}: {}", solved,
                    circumference_refusal(summary.parameters, b.max_sigma_circumference_m,
                                          !uncertainty.has_value()));
  } else {
    summary.message = solved;
  }
}

void suggest_tyre_model(ModelAdequacy& adequacy) {
  if (!adequacy.judged || adequacy.explains) return;
  adequacy.verdict +=
      "; the batch method's tyre_model: physical (or auto) fits a circumference that follows the "
      "driving state (docs/tyre-model.md)";
}

}  // namespace odocal::batch
