// The shipped example log (generated from closed-form geometry by
// tools/make_figure_eight_log.py) read and dead-reckoned end to end: with the true
// circumferences the odometry follows truth to within encoder quantisation; with the nominal
// ones it drifts.

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "odocal/estimation/dead_reckoning.hpp"
#include "odocal/estimation/start_pose.hpp"
#include "odocal/estimation/trajectory_errors.hpp"
#include "odocal/io/log_reader.hpp"

namespace odocal {
namespace {

const std::string kExample = std::string(ODOCAL_SOURCE_DIR) + "/examples/figure-eight";

TrajectoryErrors errors_with(const Log& log, const OdometryParams& params) {
  const Pose2 start = start_pose_from_truth(*log.truth, log.wheels.t_s.front());
  return trajectory_errors(dead_reckon(log.wheels, params, start),
                           reference_from_poses(*log.truth, "truth.csv"));
}

TEST(ExampleLog, TrueCircumferencesFollowTruthWithinQuantisation) {
  const Log log = read_log(kExample);
  ASSERT_TRUE(log.truth && log.imu && log.heading);
  const YAML::Node truth = YAML::LoadFile(kExample + "/truth.yaml");
  const OdometryParams true_params{truth["circumference_rl_m"].as<double>(),
                                   truth["circumference_rr_m"].as<double>(),
                                   truth["track_width_m"].as<double>()};
  const TrajectoryErrors errors = errors_with(log, true_params);
  // One tick of either wheel is c/96 = 2 cm; the heading error it causes never accumulates.
  const double tick_m = true_params.circumference_rr_m / *log.vehicle.ticks_per_rev;
  EXPECT_LT(errors.max_heading_rad, 2.0 * tick_m / true_params.track_width_m);
  EXPECT_LT(errors.max_position_m, 0.25);
  EXPECT_NEAR(errors.distance_m, 4 * 3.14159265 * 20.0, 0.5);
}

TEST(ExampleLog, NominalCircumferencesDrift) {
  const Log log = read_log(kExample);
  const TrajectoryErrors errors = errors_with(log, log.vehicle.nominal_params());
  EXPECT_GT(errors.max_position_m, 1.0);
}

}  // namespace
}  // namespace odocal
