#include "deadreckon_command.hpp"

#include <fmt/format.h>

#include <memory>
#include <optional>

#include "log_window_args.hpp"
#include "number_checks.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/dead_reckoning.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/log_preparation.hpp"
#include "odocal/estimation/motion_coverage.hpp"
#include "odocal/estimation/start_pose.hpp"
#include "odocal/estimation/trajectory_errors.hpp"
#include "odocal/io/log_reader.hpp"
#include "odocal/io/trajectory_writer.hpp"
#include "odocal/model/angle.hpp"

namespace odocal::cli {
namespace {

struct DeadreckonArgs {
  std::string log_dir;
  std::optional<double> circumference_rl_m;
  std::optional<double> circumference_rr_m;
  std::optional<double> track_width_m;
  bool plain = false;  // ignore vehicle.yaml's tyre_model
  std::string start = "auto";
  std::string out_csv;
  std::string out_tum;
  LogWindowArgs window;
};

// Where the odometry chain breaks (a wheel gap), dead reckoning restarts from the reference: the
// truth pose, else the GNSS position there with heading.csv's heading (else the dead-reckoned
// one).
Pose2 restart_pose(const Log& log, double t_s, const Pose2& carried) {
  if (log.truth) {
    if (const auto pose = interpolate_pose(*log.truth, t_s)) return *pose;
  }
  Pose2 pose = carried;
  const auto x = interpolate_linear(log.gnss.t_s, log.gnss.x_m, t_s);
  const auto y = interpolate_linear(log.gnss.t_s, log.gnss.y_m, t_s);
  if (x && y) pose.head<2>() = Eigen::Vector2d(*x, *y);
  if (log.heading) {
    if (const auto heading = interpolate_angle(log.heading->t_s, log.heading->heading_rad, t_s))
      pose.z() = carried.z() + angle_difference(*heading, carried.z());
  }
  return pose;
}

Pose2 choose_start(const Log& log, const OdometryParams& params, const std::string& start) {
  const double t0 = log.wheels.t_s.front();
  const bool use_truth = start == "truth" || (start == "auto" && log.truth.has_value());
  if (use_truth) {
    if (!log.truth)
      throw InputError({log.source + "/truth.csv", 0, ""}, "--start truth needs this file");
    return start_pose_from_truth(*log.truth, t0);
  }
  return start_pose_from_gnss(log, params);
}

void run_deadreckon(const DeadreckonArgs& args) {
  const Log input = args.window.apply(read_log(args.log_dir));
  LogPreparation prepared_by;
  const std::optional<Log> prepared = prepare_log(input, CalibrationOptions{}, prepared_by, false);
  const Log& log = prepared ? *prepared : input;
  OdometryParams params = log.vehicle.nominal_params();
  if (args.circumference_rl_m) params.circumference_rl_m = *args.circumference_rl_m;
  if (args.circumference_rr_m) params.circumference_rr_m = *args.circumference_rr_m;
  if (args.track_width_m) params.track_width_m = *args.track_width_m;

  const Pose2 start = choose_start(log, params, args.start);
  const TyreModel tyre = args.plain ? TyreModel{} : log.vehicle.tyre_model.value_or(TyreModel{});
  const WheelStream wheels = with_tyre_model(log, params, tyre);
  const PoseStream trajectory = dead_reckon(
      wheels, params, start,
      [&](double t_s, const Pose2& carried) { return restart_pose(log, t_s, carried); });
  const ReferencePath reference =
      log.truth ? reference_from_poses(*log.truth, "truth.csv")
                : reference_from_gnss(log.gnss, log.heading ? &*log.heading : nullptr);
  const TrajectoryErrors errors = trajectory_errors(trajectory, reference);

  const double duration_s = log.wheels.t_s.back() - log.wheels.t_s.front();
  // The one distance figure: wheel odometry while moving (motion_coverage.hpp).
  const double distance_m =
      motion_coverage(log, params, log.wheels.t_s.front(), log.wheels.t_s.back()).distance_m;
  fmt::print("log          {} ({} wheel samples, {:.1f} s, {:.1f} m driven)\n", log.source,
             log.wheels.size(), duration_s, distance_m);
  if (const std::string done = prepared_by.describe(); !done.empty())
    fmt::print("prepared     {}\n", done);
  fmt::print("parameters   c_RL {:.6f} m, c_RR {:.6f} m, t_R {:.4f} m{}\n",
             params.circumference_rl_m, params.circumference_rr_m, params.track_width_m,
             tyre.plain() ? "" : ", with vehicle.yaml's tyre_model");
  fmt::print("start pose   x {:.3f} m, y {:.3f} m, heading {:.2f} deg (from {})\n", start.x(),
             start.y(), deg_from_rad(start.z()),
             args.start == "auto" ? (log.truth ? "truth" : "gnss") : args.start);
  fmt::print("reference    {} ({} position samples)\n", reference.name, errors.position_samples);
  fmt::print("position     mean {:.3f} m, max {:.3f} m\n", errors.mean_position_m,
             errors.max_position_m);
  if (errors.heading_samples > 0) {
    fmt::print("heading      mean {:.3f} deg, max {:.3f} deg\n",
               deg_from_rad(errors.mean_heading_rad), deg_from_rad(errors.max_heading_rad));
  } else {
    fmt::print("heading      no heading reference in this log\n");
  }
  fmt::print("final drift  {:.3f} m = {:.3f} % of {:.1f} m driven\n", errors.final_position_m,
             distance_m > 0.0 ? 100.0 * errors.final_position_m / distance_m : 0.0, distance_m);

  if (!args.out_csv.empty()) write_trajectory_csv(trajectory, args.out_csv);
  if (!args.out_tum.empty()) write_trajectory_tum(trajectory, args.out_tum);
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
      ->add_option("--circumference-rl", args->circumference_rl_m,
                   "Rear-left circumference in m (default: vehicle.yaml)")
      ->check(finite_in(kCircumferenceM));
  command
      ->add_option("--circumference-rr", args->circumference_rr_m,
                   "Rear-right circumference in m (default: vehicle.yaml)")
      ->check(finite_in(kCircumferenceM));
  command
      ->add_option("--track-width", args->track_width_m,
                   "Rear track width in m (default: vehicle.yaml)")
      ->check(finite_in(kTrackWidthM));
  command->add_flag(
      "--plain", args->plain,
      "Constant circumferences: ignore vehicle.yaml's tyre_model (docs/tyre-model.md)");
  command
      ->add_option("--start", args->start,
                   "Start pose: truth, gnss, or auto (truth when truth.csv exists)")
      ->check(CLI::IsMember({"auto", "truth", "gnss"}));
  args->window.add_to(*command);
  command->add_option("--out", args->out_csv, "Write the trajectory as CSV (t,x,y,heading)");
  command->add_option("--tum", args->out_tum, "Write the trajectory in TUM format");
  command->callback([args] { run_deadreckon(*args); });
}

}  // namespace odocal::cli
