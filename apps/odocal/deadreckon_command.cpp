#include "deadreckon_command.hpp"

#include <fmt/format.h>

#include <limits>
#include <optional>

#include "log_window_args.hpp"
#include "number_checks.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/log_dead_reckoning.hpp"
#include "odocal/estimation/prepared_blocks.hpp"
#include "odocal/io/log_block_reader.hpp"
#include "odocal/io/trajectory_writer.hpp"
#include "odocal/model/angle.hpp"
#include "tick_smoothing_option.hpp"

namespace odocal::cli {
namespace {

struct DeadreckonArgs {
  std::string log_dir;
  LogDeadReckoningOptions options;
  std::string start = "auto";
  std::string out_csv;
  std::string out_tum;
  LogWindowArgs window;
};

// The log is read a block at a time and the trajectory written as it comes: memory does not
// grow with the drive (docs/real-data.md).
void run_deadreckon(DeadreckonArgs args) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  const double from_s = args.window.from_s.value_or(-kInfinity);
  const double to_s = args.window.to_s.value_or(kInfinity);
  {
    // The tyre model takes ax: a long log's forward offset is measured over all of it first, so
    // that every block removes the same estimate, the one calibrate removes.
    LogBlockReader first_pass(args.log_dir, {}, from_s, to_s);
    if (!dead_reckoning_tyre_model(args.options, first_pass.vehicle()).plain())
      args.options.forward_offset_mps2 =
          whole_log_forward_offset(first_pass, args.options.preparation);
  }
  LogBlockReader reader(args.log_dir, {}, from_s, to_s);
  args.options.start = args.start == "truth"  ? LogStart::kTruth
                       : args.start == "gnss" ? LogStart::kGnss
                                              : LogStart::kAuto;
  if (args.options.start == LogStart::kTruth && !reader.has_truth())
    throw InputError({args.log_dir + "/truth.csv", 0, ""}, "--start truth needs this file");
  std::optional<TrajectoryFileWriter> csv, tum;
  if (!args.out_csv.empty()) csv.emplace(args.out_csv, TrajectoryFormat::kCsv);
  if (!args.out_tum.empty()) tum.emplace(args.out_tum, TrajectoryFormat::kTum);
  const LogDeadReckoning run =
      dead_reckon_log(reader, args.options, [&](double t_s, const Pose2& pose) {
        if (csv) csv->add(t_s, pose);
        if (tum) tum->add(t_s, pose);
      });

  const TrajectoryErrors& errors = run.errors;
  fmt::print("log          {} ({} wheel samples, {:.1f} s, {:.1f} m driven)\n", reader.source(),
             run.wheel_samples, run.duration_s, run.distance_m);
  if (const std::string done = run.prepared.describe(); !done.empty())
    fmt::print("prepared     {}\n", done);
  fmt::print("parameters   c_RL {:.6f} m, c_RR {:.6f} m, t_R {:.4f} m{}\n",
             run.params.circumference_rl_m, run.params.circumference_rr_m, run.params.track_width_m,
             run.tyre_model ? ", with vehicle.yaml's tyre_model" : "");
  fmt::print("start pose   x {:.3f} m, y {:.3f} m, heading {:.2f} deg (from {})\n", run.start.x(),
             run.start.y(), deg_from_rad(run.start.z()), run.start_from);
  fmt::print("reference    {} ({} position samples)\n", run.reference_name,
             errors.position_samples);
  fmt::print("position     mean {:.3f} m, max {:.3f} m\n", errors.mean_position_m,
             errors.max_position_m);
  if (errors.heading_samples > 0) {
    fmt::print("heading      mean {:.3f} deg, max {:.3f} deg\n",
               deg_from_rad(errors.mean_heading_rad), deg_from_rad(errors.max_heading_rad));
  } else {
    fmt::print("heading      no heading reference in this log\n");
  }
  fmt::print("final drift  {:.3f} m = {:.3f} % of {:.1f} m driven\n", errors.final_position_m,
             run.distance_m > 0.0 ? 100.0 * errors.final_position_m / run.distance_m : 0.0,
             run.distance_m);

  if (csv) csv->commit();
  if (tum) tum->commit();
}

}  // namespace

void add_deadreckon_command(CLI::App& app) {
  auto args = std::make_shared<DeadreckonArgs>();
  CLI::App* command = app.add_subcommand(
      "deadreckon",
      "Integrate the wheel odometry over a whole log and report its error against "
      "truth.csv (else GNSS)");
  command->add_option("LOG", args->log_dir, "Log directory (docs/log-format.md)")->required();
  command
      ->add_option("--circumference-rl", args->options.circumference_rl_m,
                   "Rear-left circumference in m (default: vehicle.yaml)")
      ->check(finite_in(kCircumferenceM));
  command
      ->add_option("--circumference-rr", args->options.circumference_rr_m,
                   "Rear-right circumference in m (default: vehicle.yaml)")
      ->check(finite_in(kCircumferenceM));
  command
      ->add_option("--track-width", args->options.track_width_m,
                   "Rear track width in m (default: vehicle.yaml)")
      ->check(finite_in(kTrackWidthM));
  command->add_flag(
      "--plain", args->options.plain,
      "Constant circumferences: ignore vehicle.yaml's tyre_model (docs/tyre-model.md)");
  command
      ->add_option("--start", args->start,
                   "Start pose: truth, gnss, or auto (truth when truth.csv exists)")
      ->check(CLI::IsMember({"auto", "truth", "gnss"}));
  add_tick_smoothing_option(*command, args->options.tick_smoothing_s);
  args->window.add_to(*command);
  command->add_option("--out", args->out_csv, "Write the trajectory as CSV (t,x,y,heading)");
  command->add_option("--tum", args->out_tum, "Write the trajectory in TUM format");
  command->callback([args] { run_deadreckon(*args); });
}

}  // namespace odocal::cli
