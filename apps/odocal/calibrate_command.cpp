#include "calibrate_command.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "exit_codes.hpp"
#include "log_window_args.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/io/calibration_export.hpp"
#include "odocal/io/calibration_io.hpp"
#include "odocal/io/log_doctor.hpp"
#include "odocal/io/log_reader.hpp"
#include "odocal/io/output_file.hpp"

namespace odocal::cli {
namespace {

struct CalibrateArgs {
  std::string log_dir;
  std::optional<std::string> method;
  std::string config_file;
  std::string json_file;
  std::optional<std::string> reference;
  std::string vehicle_out;
  bool force = false;
  std::string ros2_out;
  bool print_config = false;
  LogWindowArgs window;
};

CalibrationConfig effective_config(const CalibrateArgs& args) {
  CalibrationConfig config;
  if (!args.config_file.empty()) config = read_calibration_config(args.config_file);
  if (args.method) config.method = *parse_enum<CalibrationMethod>(*args.method);
  if (args.reference) config.common.reference.mode = *parse_enum<ReferenceMode>(*args.reference);
  return config;
}

// The log's own vehicle.yaml holds the nominal vehicle its calibrations are measured from;
// replacing it would make the next calibration of the same log start from this one's answer.
void refuse_log_vehicle_file(const CalibrateArgs& args) {
  if (args.vehicle_out.empty()) return;
  std::error_code error;
  if (std::filesystem::equivalent(args.vehicle_out,
                                  std::filesystem::path(args.log_dir) / "vehicle.yaml", error)) {
    throw CLI::ValidationError("--vehicle-out",
                               args.vehicle_out +
                                   " is the log's own vehicle.yaml (its nominal vehicle): write "
                                   "the calibrated vehicle elsewhere");
  }
}

void run_calibrate(const CalibrateArgs& args) {
  const CalibrationConfig config = effective_config(args);
  if (args.print_config) {
    fmt::print("{}", config_to_yaml(config));
    return;
  }
  if (args.log_dir.empty()) throw CLI::RequiredError("LOG");
  refuse_log_vehicle_file(args);
  LogReadOptions read_options;
  read_options.read_truth = false;  // estimators never see the truth
  const Log log = args.window.apply(read_log(args.log_dir, read_options));
  // The doctor's warnings do not stop a calibration, but can explain what it finds (a track
  // the wheels do not roll on, an IMU clock that cannot be checked): shown with its report.
  std::optional<std::vector<std::string>> doctor_warnings;
  if (!args.force) {
    // The doctor's blocking findings (a flipped sign, a unit, a clock) make any estimate wrong.
    const Diagnosis diagnosis = doctor_log(log, args.log_dir);
    if (diagnosis.blocking()) {
      std::string first;
      for (const Finding& f : diagnosis.findings) {
        if (f.severity == FindingSeverity::kBlocking) {
          first = describe(f);
          break;
        }
      }
      throw NotUsableResult(
          fmt::format("the log has input mistakes that would make the "
                      "calibration wrong, first: {} -- run `odocal doctor {}` "
                      "for all, or --force to calibrate anyway",
                      first, args.log_dir));
    }
    doctor_warnings.emplace();
    for (const Finding& f : diagnosis.findings)
      if (f.severity == FindingSeverity::kWarning) doctor_warnings->push_back(describe(f));
  }
  const AnyCalibrationSummary summary = calibrate(log, config);
  const CalibrationSummary& result = core(summary);
  fmt::print("{}", full_report(summary));
  if (doctor_warnings) {
    for (const std::string& warning : *doctor_warnings) fmt::print("{:<13}{}\n", "doctor", warning);
  }
  // The JSON says why when the result is not usable; the exports carry usable results only.
  if (!args.json_file.empty()) {
    nlohmann::json json = summary_to_json(summary, config);
    if (doctor_warnings) json["doctor_warnings"] = *doctor_warnings;
    write_output_file(args.json_file, json.dump(2) + "\n");
  }
  if (!result.usable()) throw NotUsableResult(result.message);
  const auto* batch = std::get_if<BatchSummary>(&summary);
  if (!args.vehicle_out.empty()) {
    // The antenna where the batch found it: layer 1 and the next calibration take it from there.
    VehicleConfig found = log.vehicle;
    if (const auto antenna = batch ? fitted_antenna_place(*batch) : std::nullopt)
      found.gnss_position_m = antenna;
    write_calibrated_vehicle(found, result.estimate, args.vehicle_out, result.tyre_model);
  }
  if (!args.ros2_out.empty()) {
    write_ros2_diff_drive_parameters(log.vehicle, result.estimate, args.ros2_out, result.tyre_model,
                                     batch ? batch->reference_circumference : std::nullopt);
  }
}

}  // namespace

void add_calibrate_command(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* command =
      app.add_subcommand("calibrate", "Estimate the rear wheel circumferences from a log");
  command->add_option("LOG", args->log_dir, "Log directory (docs/log-format.md)");
  command
      ->add_option("--method", args->method,
                   "iterative (the paper), fixed-p, augmented, or batch (maximum likelihood over "
                   "the whole log)")
      ->check(CLI::IsMember(enum_name_list<CalibrationMethod>()));
  command->add_option("--config", args->config_file,
                      "Calibration options YAML (docs/calibration.md; see --print-config)");
  command
      ->add_option("--reference", args->reference,
                   "Layer-1 reference: filter (the paper) or smoother")
      ->check(CLI::IsMember(enum_name_list<ReferenceMode>()));
  command->add_flag("--print-config", args->print_config,
                    "Print the configuration (defaults, --config, --method, --reference) as "
                    "commented YAML and exit; feed it back with --config");
  args->window.add_to(*command);
  command->add_option("--json", args->json_file, "Write the full result as JSON");
  command->add_flag("--force", args->force,
                    "Calibrate even when `odocal doctor` finds input mistakes that block it");
  command->add_option("--vehicle-out", args->vehicle_out,
                      "Write vehicle.yaml with the calibrated circumferences and track width");
  command->add_option("--ros2-out", args->ros2_out,
                      "Write ROS 2 diff_drive_controller parameters (radius and separation "
                      "multipliers)");
  command->callback([args] { run_calibrate(*args); });
}

}  // namespace odocal::cli
