#include "validate_command.hpp"

#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "log_window_args.hpp"
#include "number_checks.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/drift_validation.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/estimation/log_preparation.hpp"
#include "odocal/io/calibration_export.hpp"
#include "odocal/io/calibration_io.hpp"
#include "odocal/io/log_reader.hpp"
#include "odocal/io/output_file.hpp"
#include "tick_smoothing_option.hpp"

namespace odocal::cli {
namespace {

struct ValidateArgs {
  std::string log_dir;
  std::string params_file;
  DriftValidationOptions options;
  std::string reference = "smoother";
  std::string config_file;
  LogWindowArgs window;
  std::string json_file;
};

nlohmann::json statistics_json(const DriftStatistics& s) {
  return {{"windows", s.windows},
          {"median_end_error_m", s.median_end_error_m},
          {"p95_end_error_m", s.p95_end_error_m},
          {"median_drift_percent", s.median_drift_percent},
          {"p95_drift_percent", s.p95_drift_percent}};
}

void run_validate(const ValidateArgs& args) {
  const OdometryParams calibrated = read_calibrated_parameters(args.params_file);
  const TyreModel calibrated_tyre = read_calibrated_tyre_model(args.params_file);
  LogReadOptions read_options;
  read_options.read_truth = false;
  Log input = args.window.apply(read_log(args.log_dir, read_options));
  if (const auto antenna = read_calibrated_antenna(args.params_file);
      adopt_found_antenna(input.vehicle, antenna)) {
    fmt::print(
        "antenna      the result's, {:+.3f} m ahead and {:+.3f} m left of the rear axle "
        "(vehicle.yaml states none)\n",
        antenna->x(), antenna->y());
  }
  CalibrationOptions options;
  if (!args.config_file.empty()) options = read_calibration_config(args.config_file).common;
  options.reference.mode = *parse_enum<ReferenceMode>(args.reference);
  LogPreparation prepared_by;
  const std::optional<Log> prepared = prepare_log(input, options, prepared_by);
  const Log& log = prepared ? *prepared : input;
  if (const std::string done = prepared_by.describe(); !done.empty())
    fmt::print("log          {}\n", done);
  const ReferenceTrajectory reference =
      compute_reference(log, options.reference, ReferenceCovariance::kKeep);
  // Each parameter set with its own tyre model: vehicle.yaml's for the nominal one (if any), the
  // result's for the calibrated one.
  const OdometryParams nominal = log.vehicle.nominal_params();
  const WheelStream nominal_wheels =
      with_tyre_model(log, nominal, log.vehicle.tyre_model.value_or(TyreModel{}));
  const WheelStream calibrated_wheels = with_tyre_model(log, calibrated, calibrated_tyre);
  if (!calibrated_tyre.plain())
    fmt::print(
        "tyre model   the result's condition-dependent circumference (docs/tyre-model.md)\n");
  const DriftValidation v = validate_drift(nominal_wheels, calibrated_wheels, reference, nominal,
                                           calibrated, args.options);
  fmt::print("{} windows of {:.0f} s{}, dead-reckoned from the {} reference at their start:\n",
             v.nominal_statistics.windows, args.options.window_s,
             args.options.step_s > 0.0 ? fmt::format(" starting every {:g} s", args.options.step_s)
                                       : std::string(),
             args.reference);
  fmt::print("{:<12} {:>18} {:>16} {:>18} {:>16}\n", "parameters", "median drift [%]",
             "p95 drift [%]", "median end [m]", "p95 end [m]");
  const auto row = [](const char* name, const DriftStatistics& s) {
    fmt::print("{:<12} {:>18.3f} {:>16.3f} {:>18.2f} {:>16.2f}\n", name, s.median_drift_percent,
               s.p95_drift_percent, s.median_end_error_m, s.p95_end_error_m);
  };
  row("nominal", v.nominal_statistics);
  row("calibrated", v.calibrated_statistics);
  // What the reference's own uncertainty alone would show (drift_validation.hpp): a drift near it
  // measures the reference, not the parameters.
  fmt::print("{:<12} {:>18.3f} {:>16} {:>18.2f} {:>16}   the reference's own uncertainty\n",
             "reference", v.reference->median_drift_percent, "-", v.reference->median_end_error_m,
             "-");
  if (!args.json_file.empty()) {
    nlohmann::json windows = nlohmann::json::array();
    for (std::size_t i = 0; i < v.nominal.size(); ++i) {
      windows.push_back({{"start_s", v.nominal[i].start_s},
                         {"distance_m", v.nominal[i].distance_m},
                         {"nominal_end_error_m", v.nominal[i].end_error_m},
                         {"calibrated_end_error_m", v.calibrated[i].end_error_m},
                         {"reference_rms_m", v.reference->rms_m[i]}});
    }
    write_output_file(
        args.json_file,
        nlohmann::json{{"window_s", args.options.window_s},
                       {"step_s", args.options.step_s},
                       {"tick_smoothing_s", args.options.tick_smoothing_s},
                       {"reference", args.reference},
                       {"nominal", statistics_json(v.nominal_statistics)},
                       {"calibrated", statistics_json(v.calibrated_statistics)},
                       {"reference_uncertainty",
                        {{"median_end_error_m", v.reference->median_end_error_m},
                         {"median_drift_percent", v.reference->median_drift_percent}}},
                       {"windows", windows}}
                .dump(2) +
            "\n");
  }
}

}  // namespace

void add_validate_command(CLI::App& app) {
  auto args = std::make_shared<ValidateArgs>();
  CLI::App* command = app.add_subcommand(
      "validate",
      "Held-out drift: dead-reckon windows of the log from the reference pose as if GNSS were "
      "lost there, with nominal and calibrated parameters");
  command->add_option("LOG", args->log_dir, "Log directory (docs/log-format.md)")->required();
  command->add_option("--params", args->params_file, "Calibration result (odocal calibrate --json)")
      ->required();
  command->add_option("--window", args->options.window_s, "Window length, s")
      ->capture_default_str()
      ->check(finite_in(1.0, 86400.0));
  command
      ->add_option("--step", args->options.step_s,
                   "Start a window every STEP s (overlapping windows); 0: every window length")
      ->capture_default_str()
      ->check(finite_in(0.0, 86400.0));
  command
      ->add_option("--min-distance", args->options.min_window_distance_m,
                   "Skip windows with less driving than this, m")
      ->capture_default_str()
      ->check(finite_in(0.0, 1e6));
  add_tick_smoothing_option(*command, args->options.tick_smoothing_s);
  command->add_option("--reference", args->reference, "Reference pose: smoother or filter")
      ->capture_default_str()
      ->check(CLI::IsMember(enum_name_list<ReferenceMode>()));
  command->add_option("--config", args->config_file,
                      "Calibration options YAML (as calibrate --config): its reference options "
                      "are used; the mode is --reference");
  args->window.add_to(*command);
  command->add_option("--json", args->json_file, "Write the statistics and every window as JSON");
  command->callback([args] { run_validate(*args); });
}

}  // namespace odocal::cli
