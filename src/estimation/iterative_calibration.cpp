#include "odocal/estimation/iterative_calibration.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>

#include "calibration_report.hpp"
#include "calibration_run.hpp"
#include "odocal/estimation/circumference_ls.hpp"
#include "odocal/estimation/odometry_ekf.hpp"

namespace odocal {
namespace {

enum class ProcessCovariance { kDecaying, kFixed };

std::string unseparable_message(const CircumferenceFit& fit, double max_condition_number) {
  if (!fit.circumference_m.allFinite() || std::isnan(fit.condition_number)) {
    return "the least-squares solution is not finite: the filtered odometry diverged (a sensor "
           "value far outside its range, or a wheel stream that does not match the GNSS track)";
  }
  return fmt::format(
      "the least-squares problem cannot separate c_RL and c_RR (condition number {:.3g} > "
      "{:.3g}): the log needs more distance and more turning",
      fit.condition_number, max_condition_number);
}

bool separable(const CircumferenceFit& fit, double max_condition_number) {
  return std::isfinite(fit.condition_number) && fit.condition_number <= max_condition_number &&
         fit.circumference_m.allFinite();
}

// The last iteration's change of the circumferences (from the nominal ones after a single
// iteration), in units of the estimate's 1-sigma; the larger of the two wheels.
double last_step_in_sigma(const IterativeSummary& summary) {
  const IterationRecord& last = summary.iterations.back();
  const double previous_rl =
      summary.iterations.size() > 1
          ? summary.iterations[summary.iterations.size() - 2].circumference_rl_m
          : summary.nominal.circumference_rl_m;
  const double previous_rr =
      summary.iterations.size() > 1
          ? summary.iterations[summary.iterations.size() - 2].circumference_rr_m
          : summary.nominal.circumference_rr_m;
  return std::max(std::abs(last.circumference_rl_m - previous_rl) / summary.sigma_rl_m(),
                  std::abs(last.circumference_rr_m - previous_rr) / summary.sigma_rr_m());
}

// Layers 2 and 3 repeated (section 4); the estimate is the iteration with the lowest score.
void run_loop(CalibrationRun& run, const IterativeOptions& options,
              const CalibrationOptions& common, ProcessCovariance process,
              IterativeSummary& summary) {
  const ReferenceTrajectory& reference = run.reference();
  const WheelStream& wheels = run.log().wheels;
  OdometryParams params = summary.nominal;
  std::vector<Pose2> x_hat;
  double best_score = std::numeric_limits<double>::infinity();
  int since_best = 0;
  CircumferenceFit best_fit;
  bool stopped_by_patience = false;
  for (int i = 1; i <= options.max_iterations; ++i) {
    const OdometryEkfNoise noise{process == ProcessCovariance::kDecaying
                                     ? decaying_process_diagonal(i, options.decay_exponent_q)
                                     : options.fixed_process_diagonal,
                                 common.measurement_diagonal};
    run_odometry_ekf(wheels, reference, params, noise, x_hat);
    const CircumferenceFit fit =
        summary.difference_identifiable
            ? fit_circumferences(wheels, reference, x_hat, params.track_width_m, options.ls_weights,
                                 options.ls_window_samples)
            : fit_common_scale(wheels, reference, x_hat, params.track_width_m, options.ls_weights,
                               options.ls_window_samples,
                               Eigen::Vector2d(summary.nominal.circumference_rl_m,
                                               summary.nominal.circumference_rr_m));
    if (!separable(fit, options.max_condition_number)) {
      summary.termination = Termination::kNotIdentifiable;
      summary.message = unseparable_message(fit, options.max_condition_number);
      summary.condition_number = fit.condition_number;
      break;
    }
    params.circumference_rl_m = fit.circumference_m(0);
    params.circumference_rr_m = fit.circumference_m(1);
    IterationRecord record{i, params.circumference_rl_m, params.circumference_rr_m,
                           run.evaluator().evaluate(params), 0.0};
    record.score = record.errors.mean_position_m +
                   options.heading_weight_m_per_rad * record.errors.mean_heading_rad;
    summary.iterations.push_back(record);
    if (record.score < best_score) {
      best_score = record.score;
      since_best = 0;
      best_fit = fit;
      summary.chosen_iteration = i;
    } else if (++since_best >= options.patience) {
      stopped_by_patience = true;
      break;
    }
  }
  if (summary.chosen_iteration == 0) return;  // not even one fit: the estimate stays nominal
  const IterationRecord& chosen =
      summary.iterations[static_cast<std::size_t>(summary.chosen_iteration - 1)];
  summary.estimate.circumference_rl_m = chosen.circumference_rl_m;
  summary.estimate.circumference_rr_m = chosen.circumference_rr_m;
  summary.covariance = best_fit.covariance;
  if (summary.termination != Termination::kConverged) return;
  summary.condition_number = best_fit.condition_number;
  const int ran = static_cast<int>(summary.iterations.size());
  if (stopped_by_patience) {
    summary.message = fmt::format(
        "minimum of the dead-reckoning errors at iteration {}; stopped after {} iterations "
        "without a new minimum",
        summary.chosen_iteration, options.patience);
  } else if (summary.chosen_iteration < ran) {
    summary.message =
        fmt::format("reached {} iterations; minimum of the dead-reckoning errors at iteration {}",
                    options.max_iterations, summary.chosen_iteration);
  } else if (const double step_sigma = last_step_in_sigma(summary);
             step_sigma < options.step_tolerance_sigma) {
    summary.message = fmt::format(
        "reached {} iterations with the dead-reckoning error still falling, by steps of {:.2g} "
        "sigma of the estimate",
        options.max_iterations, step_sigma);
  } else {
    summary.termination = Termination::kNoConvergence;
    summary.message = fmt::format(
        "the estimate still moved by {:.2g} sigma at the last of {} iterations: raise "
        "max_iterations",
        step_sigma, options.max_iterations);
  }
}

IterativeSummary calibrate_with(const Log& log, const IterativeOptions& options,
                                const CalibrationOptions& common, ProcessCovariance process) {
  require_valid("iterative", options.validate());
  IterativeSummary summary;
  CalibrationRun run(log, common,
                     process == ProcessCovariance::kDecaying ? CalibrationMethod::kIterative
                                                             : CalibrationMethod::kFixedP,
                     summary);
  run_loop(run, options, common, process, summary);
  run.finish(summary);
  return summary;
}

}  // namespace

OptionTable<IterativeOptions> IterativeOptions::fields() {
  using O = IterativeOptions;
  static const std::array<OptionField<O>, 9> kFields{{
      {"decay_exponent_q", "1", 1.0, 2.0, "q of the decaying process covariance (eq. 13b)",
       &O::decay_exponent_q},
      {"fixed_process_diagonal", "[m^2, m^2, rad^2]", 1e-12, 1e12,
       "fixed-p: the constant process covariance P", &O::fixed_process_diagonal},
      {"ls_weights", "[1/m^2, 1/m^2, 1/rad^2]", 1e-12, 1e12, "W of the least squares (section 3.3)",
       &O::ls_weights},
      {"ls_window_samples", "1", 1.0, 1e5,
       "rows of eq. 12 summed over this many samples (1: the paper)", &O::ls_window_samples},
      {"max_iterations", "1", 1.0, 1e4, "at most this many iterations", &O::max_iterations},
      {"patience", "1", 1.0, 1e4, "stop after this many iterations without a new minimum",
       &O::patience},
      {"heading_weight_m_per_rad", "m/rad", 0.0, 1e6,
       "score = mean position error + this * mean heading error", &O::heading_weight_m_per_rad},
      {"max_condition_number", "1", 1.0, 1e300,
       "above this condition number of the LS rows c_RL and c_RR count as not separable",
       &O::max_condition_number},
      {"step_tolerance_sigma", "sigma", 0.0, 1e3,
       "at the iteration limit: converged if the last step moved the estimate less than this",
       &O::step_tolerance_sigma},
  }};
  return kFields;
}

std::string IterativeOptions::validate() const { return check_option_ranges(fields(), *this); }

std::string IterativeSummary::full_report() const {
  std::string text = report_heading(*this);
  if (!difference_identifiable) text += fmt::format("{:<13}{}\n", "note", identifiability);
  text += fmt::format("{:<13}{} of {}{}\n", "iteration", chosen_iteration, iterations.size(),
                      usable() ? ": " + message : std::string());
  return text + report_ending(*this);
}

IterativeSummary calibrate_iterative(const Log& log, const IterativeOptions& options,
                                     const CalibrationOptions& common) {
  return calibrate_with(log, options, common, ProcessCovariance::kDecaying);
}

IterativeSummary calibrate_fixed_p(const Log& log, const IterativeOptions& options,
                                   const CalibrationOptions& common) {
  return calibrate_with(log, options, common, ProcessCovariance::kFixed);
}

}  // namespace odocal
