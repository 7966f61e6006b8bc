#include "calibrate_command.hpp"

#include <fmt/format.h>

#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "odocal/error.hpp"
#include "odocal/io/calibration_export.hpp"
#include "odocal/io/calibration_io.hpp"
#include "odocal/io/log_reader.hpp"
#include "odocal/model/angle.hpp"

namespace odocal::cli {
namespace {

struct CalibrateArgs {
  std::string log_dir;
  std::optional<std::string> method;
  std::string config_file;
  std::string json_file;
  std::optional<std::string> reference;
  std::string vehicle_out;
  std::string ros2_out;
};

void run_calibrate(const CalibrateArgs& args) {
  CalibrationOptions options;
  if (!args.config_file.empty()) options = read_calibration_options(args.config_file);
  if (args.method) options.method = *parse_method(*args.method);
  if (args.reference) {
    options.reference.mode =
        *args.reference == "smoother" ? ReferenceMode::kSmoother : ReferenceMode::kFilter;
  }
  LogReadOptions read_options;
  read_options.read_truth = false;  // estimators never see the truth
  const Log log = read_log(args.log_dir, read_options);
  const CalibrationResult result = calibrate(log, options);
  print_calibration_report(result);
  if (!args.json_file.empty()) {
    std::ofstream out(args.json_file);
    out << result_to_json(result, options).dump(2) << "\n";
    if (!out) throw Error("cannot write " + args.json_file);
  }
  if (!args.vehicle_out.empty())
    write_calibrated_vehicle(log.vehicle, result.estimate, args.vehicle_out);
  if (!args.ros2_out.empty())
    write_ros2_diff_drive_parameters(log.vehicle, result.estimate, args.ros2_out);
}

void print_errors(const char* label, const DeadReckoningSummary& s) {
  fmt::print("{:<13}mean {:.3f} m / {:.3f} deg, max {:.3f} m / {:.3f} deg\n", label,
             s.mean_position_m, deg_from_rad(s.mean_heading_rad), s.max_position_m,
             deg_from_rad(s.max_heading_rad));
}

// The extra unknowns the user asked for, and what the log could not identify.
void print_batch_parameters(const CalibrationResult& r) {
  for (const EstimatedParameter& p : r.parameters) {
    if (!p.estimated || p.name.starts_with("circumference")) continue;
    fmt::print("{:<13}{} = {:.6g} (1-sigma {:.3g})\n", "parameter", p.name, p.value, p.sigma);
  }
  fmt::print("observable   {}\n", r.identifiability);
}

}  // namespace

void print_calibration_report(const CalibrationResult& r) {
  fmt::print("method       {} ({} reference samples, {:.1f} m, heading from {})\n",
             method_name(r.method), r.reference_samples, r.distance_m, r.reference_heading_source);
  const auto line = [](const char* name, double estimate, double nominal, double sigma) {
    fmt::print("{}         {:.6f} m ({:+.3f} mm from nominal, 1-sigma {:.3f} mm)\n", name, estimate,
               1e3 * (estimate - nominal), 1e3 * sigma);
  };
  line("c_RL", r.estimate.circumference_rl_m, r.nominal.circumference_rl_m,
       std::sqrt(r.covariance(0, 0)));
  line("c_RR", r.estimate.circumference_rr_m, r.nominal.circumference_rr_m,
       std::sqrt(r.covariance(1, 1)));
  if (r.method == CalibrationMethod::kBatch) {
    print_batch_parameters(r);
  } else if (!r.difference_identifiable) {
    fmt::print("note         {}\n", r.identifiability);
  }
  if (r.method == CalibrationMethod::kBatch) {
    fmt::print("solver       {}\n", r.termination);
  } else if (r.method != CalibrationMethod::kAugmented) {
    fmt::print("iteration    {} of {}: {}\n", r.chosen_iteration, r.iterations.size(),
               r.termination);
  }
  fmt::print("dead reckoning of the whole log against the reference:\n");
  print_errors("  before", r.before);
  print_errors("  after", r.after);
}

void add_calibrate_command(CLI::App& app) {
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* command =
      app.add_subcommand("calibrate", "Estimate the rear wheel circumferences from a log");
  command->add_option("LOG", args->log_dir, "Log directory (docs/log-format.md)")->required();
  command
      ->add_option("--method", args->method,
                   "iterative (the paper), fixed-p, augmented, or batch (maximum likelihood over "
                   "the whole log)")
      ->check(CLI::IsMember({"iterative", "fixed-p", "augmented", "batch"}));
  command->add_option("--config", args->config_file,
                      "Calibration options YAML (docs/calibration.md)");
  command
      ->add_option("--reference", args->reference,
                   "Layer-1 reference: filter (the paper) or smoother")
      ->check(CLI::IsMember({"filter", "smoother"}));
  command->add_option("--json", args->json_file, "Write the full result as JSON");
  command->add_option("--vehicle-out", args->vehicle_out,
                      "Write vehicle.yaml with the calibrated circumferences and track width");
  command->add_option("--ros2-out", args->ros2_out,
                      "Write ROS 2 diff_drive_controller parameters (radius and separation "
                      "multipliers)");
  command->callback([args] { run_calibrate(*args); });
}

}  // namespace odocal::cli
