#include "odocal/estimation/log_dead_reckoning.hpp"

#include <fmt/format.h>

#include "odocal/data/stream_columns.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/dead_reckoning.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/motion_coverage.hpp"
#include "odocal/estimation/prepared_blocks.hpp"
#include "odocal/estimation/start_pose.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/mounted_position.hpp"

namespace odocal {
namespace {

// Where the odometry chain breaks (a wheel gap), dead reckoning restarts from the reference: the
// truth pose, else the GNSS position there (the antenna's: taken back to the axle) with
// heading.csv's heading (else the dead-reckoned one).
Pose2 restart_pose(const Log& log, double t_s, const Pose2& carried) {
  if (log.truth) {
    if (const auto pose = interpolate_pose(*log.truth, t_s)) return *pose;
  }
  Pose2 pose = carried;
  if (log.heading) {
    if (const auto heading = interpolate_angle(log.heading->t_s, log.heading->heading_rad, t_s))
      pose.z() = carried.z() + angle_difference(*heading, carried.z());
  }
  const auto x = interpolate_linear(log.gnss.t_s, log.gnss.x_m, t_s);
  const auto y = interpolate_linear(log.gnss.t_s, log.gnss.y_m, t_s);
  if (x && y) {
    const Eigen::Vector2d antenna = log.vehicle.gnss_position_m.value_or(Eigen::Vector2d::Zero());
    pose.head<2>() = Eigen::Vector2d(*x, *y) - (mounted_position(pose, antenna) - pose.head<2>());
  }
  return pose;
}

// The dead-reckoned poses moved to the antenna, which the fixes are of (vehicle.yaml's gnss_x_m,
// gnss_y_m), for comparing with them.
PoseStream at_antenna(PoseStream trajectory, const VehicleConfig& vehicle) {
  if (!vehicle.gnss_position_m) return trajectory;
  for (Pose2& pose : trajectory.pose)
    pose.head<2>() = mounted_position(pose, *vehicle.gnss_position_m);
  return trajectory;
}

ReferencePath reference_of(const Log& log, bool truth) {
  if (truth) {
    if (log.truth) return reference_from_poses(*log.truth, "truth.csv");
    return ReferencePath{"truth.csv", {}, {}, {}, {}, {}};
  }
  return reference_from_gnss(log.gnss, log.heading ? &*log.heading : nullptr);
}

}  // namespace

TyreModel dead_reckoning_tyre_model(const LogDeadReckoningOptions& options,
                                    const VehicleConfig& vehicle) {
  return options.plain ? TyreModel{} : vehicle.tyre_model.value_or(TyreModel{});
}

LogDeadReckoning dead_reckon_log(LogBlockSource& source, const LogDeadReckoningOptions& options,
                                 const std::function<void(double, const Pose2&)>& on_pose) {
  LogDeadReckoning run;
  BlockPreparation blocks(source, options.preparation, run.prepared, options.forward_offset_mps2);
  run.params = source.vehicle().nominal_params();
  if (options.circumference_rl_m) run.params.circumference_rl_m = *options.circumference_rl_m;
  if (options.circumference_rr_m) run.params.circumference_rr_m = *options.circumference_rr_m;
  if (options.track_width_m) run.params.track_width_m = *options.track_width_m;
  const TyreModel tyre = dead_reckoning_tyre_model(options, source.vehicle());
  run.tyre_model = !tyre.plain();
  const bool truth =
      options.start == LogStart::kTruth || (options.start == LogStart::kAuto && source.has_truth());
  run.start_from = truth ? "truth" : "gnss";
  const bool truth_reference = source.has_truth();
  run.reference_name = truth_reference        ? "truth.csv"
                       : source.has_heading() ? "gnss.csv + heading.csv"
                                              : "gnss.csv";

  TrajectoryErrorSum errors;
  std::optional<std::pair<double, Pose2>> carried;  // the last pose so far
  double first_t_s = 0.0;
  while (const std::optional<PreparedBlock> block = blocks.next()) {
    const Log& context = block->context;
    const auto [first, last] = core_rows(*block, context.wheels.t_s);
    if (first >= last) continue;
    // The block's margins hold every neighbour that a core sample's tick average reaches.
    const WheelStream counted =
        dequantised_ticks(with_tyre_model(context, run.params, tyre), options.tick_smoothing_s);
    // The piece: the pose carried from the block before, then this block's own samples.
    WheelStream piece = stream_rows(counted, first, last);
    if (carried) {
      WheelStream before;
      before.unit_rear = counted.unit_rear;
      before.t_s = {carried->first};
      before.rev_rl = before.rev_rr = {0.0};
      if (!counted.rev_fl.empty()) before.rev_fl = before.rev_fr = {0.0};
      if (!counted.side_slip_rad.empty()) before.side_slip_rad = {0.0F};
      append_stream(before, piece);
      piece = std::move(before);
    } else {
      first_t_s = piece.t_s.front();
      if (truth && !context.truth) {
        throw InsufficientDataError(fmt::format(
            "truth.csv has no sample near the first wheel sample at {} s: it cannot give the "
            "start pose",
            first_t_s));
      }
      const Log core = core_log(*block);
      run.start = truth ? start_pose_from_truth(*context.truth, first_t_s)
                        : start_pose_from_gnss(core, run.params);
    }
    const Pose2 start = carried ? carried->second : run.start;
    const PoseStream trajectory =
        dead_reckon(piece, run.params, start,
                    [&](double t_s, const Pose2& at) { return restart_pose(context, t_s, at); });
    errors.add(truth_reference ? trajectory : at_antenna(trajectory, context.vehicle),
               reference_of(context, truth_reference));
    for (std::size_t k = carried ? 1 : 0; k < trajectory.size(); ++k)
      on_pose(trajectory.t_s[k], trajectory.pose[k]);
    run.distance_m +=
        motion_coverage(context, run.params, trajectory.t_s.front(), trajectory.t_s.back())
            .distance_m;
    run.wheel_samples += last - first;
    carried = {trajectory.t_s.back(), trajectory.pose.back()};
  }
  source.finish();
  if (!carried) throw InsufficientDataError("the log has no wheel samples to dead-reckon");
  run.duration_s = carried->first - first_t_s;
  run.errors = errors.result(run.reference_name);
  return run;
}

}  // namespace odocal
