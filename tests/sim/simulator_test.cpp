// The simulator end to end: its logs read back through the log reader; ideal mode dead-reckons
// onto truth within encoder quantisation; sensor noise has its configured sigma; seeds separate.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <numeric>

#include "../support/temp_log_dir.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/dead_reckoning.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/trajectory_errors.hpp"
#include "odocal/io/log_reader.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/sim/vehicle_dynamics.hpp"

namespace odocal::sim {
namespace {

using odocal::testing::TempLogDir;

struct Simulated {
  SimulatedDrive drive;
  Log log;
};

Simulated simulate_and_read(const Scenario& scenario, const TempLogDir& dir) {
  SimulatedDrive drive = simulate(scenario);
  write_simulated_log(drive, scenario, dir.path());
  return {std::move(drive), read_log(dir.path())};
}

TrajectoryErrors errors_with_true_params(const Simulated& run) {
  const PoseStream trajectory =
      dead_reckon(run.log.wheels, run.drive.true_params, run.log.truth->pose[0]);
  return trajectory_errors(trajectory, reference_from_poses(*run.log.truth, "truth.csv"));
}

// Largest distance of the true path from its start: how far a start-heading error can swing it.
double largest_radius_m(const Simulated& run) {
  const PoseStream& truth = *run.log.truth;
  double radius = 0.0;
  for (const Pose2& pose : truth.pose)
    radius = std::max(radius, (pose.head<2>() - truth.pose.front().head<2>()).norm());
  return radius;
}

// The encoders start between ticks at random phases: the first counts are cut differently per
// wheel, a heading error of up to one tick of each wheel over the track width for the whole
// drive, on top of the bounded one of every later count.
double quantisation_heading_bound_rad(const Simulated& run, const Scenario& scenario) {
  const double tick_m = run.drive.true_params.circumference_rl_m / scenario.wheels.ticks_per_rev;
  return 2.0 * tick_m / scenario.vehicle.track_width_m;
}

double rms(const std::vector<double>& values) {
  return std::sqrt(std::inner_product(values.begin(), values.end(), values.begin(), 0.0) /
                   static_cast<double>(values.size()));
}

TEST(Simulator, IdealCircuitDeadReckonsWithinQuantisation) {
  const TempLogDir dir;
  Scenario scenario = load_scenario("circuit");  // 3 laps, 96 ticks/rev, 16-bit counters
  scenario.ideal = true;
  const Simulated run = simulate_and_read(scenario, dir);
  ASSERT_GT(run.drive.distance_m, 13000.0);
  const TrajectoryErrors errors = errors_with_true_params(run);
  // Cumulative ticks are floored, never accumulated: heading error stays within one tick of
  // each wheel over the track width, however long the drive.
  const double heading_bound = quantisation_heading_bound_rad(run, scenario);
  EXPECT_LT(errors.max_heading_rad, heading_bound);
  // So the position error is the start-phase rotation plus a small random walk, not a drift
  // that grows with the 13.5 km driven.
  EXPECT_LT(errors.max_position_m, heading_bound * largest_radius_m(run) + 1.0);
}

TEST(Simulator, IdealCircuitWithExactWheelAnglesHasOnlyModelDiscretisation) {
  const TempLogDir dir;
  Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  scenario.wheels.output = WheelUnit::kRadians;
  const TrajectoryErrors errors = errors_with_true_params(simulate_and_read(scenario, dir));
  EXPECT_LT(errors.max_position_m, 0.05);
  EXPECT_LT(errors.max_heading_rad, 1e-6);
}

TEST(Simulator, TickCountsAreCutAtTheConfiguredEncoderPhase) {
  // Same seeds, so the same start counts and motion: the ticks are floor(phase + angle in ticks)
  // past the start, with the exact wheel angles of the radians run.
  Scenario scenario = load_scenario("parking");
  scenario.ideal = true;
  scenario.wheels.counter_bits = 0;
  scenario.wheels.output = WheelUnit::kRadians;
  const SimulatedDrive angles = simulate(scenario);
  scenario.wheels.output = WheelUnit::kTicks;
  const double ticks_per_rad = scenario.wheels.ticks_per_rev / (2.0 * std::numbers::pi);
  for (const double phase : {0.0, 0.3, 0.85}) {
    scenario.wheels.start_phase = phase;
    const SimulatedDrive ticks = simulate(scenario);
    ASSERT_EQ(ticks.wheel_rl.size(), angles.wheel_rl.size());
    int mismatches = 0;
    for (std::size_t k = 0; k < ticks.wheel_rl.size(); ++k) {
      mismatches += ticks.wheel_rl[k] - ticks.wheel_rl[0] !=
                    std::floor(phase + angles.wheel_rl[k] * ticks_per_rad) - std::floor(phase);
      mismatches += ticks.wheel_rr[k] - ticks.wheel_rr[0] !=
                    std::floor(phase + angles.wheel_rr[k] * ticks_per_rad) - std::floor(phase);
    }
    EXPECT_EQ(mismatches, 0) << phase;
  }
}

TEST(Simulator, ParkingReversesWithSignedCountsAndFollowsTruth) {
  const TempLogDir dir;
  Scenario scenario = load_scenario("parking");
  scenario.ideal = true;
  const Simulated run = simulate_and_read(scenario, dir);
  const auto& rl = run.log.wheels.rev_rl;
  EXPECT_LT(*std::min_element(rl.begin(), rl.end()), 0.0);
  EXPECT_GT(run.drive.distance_m, 300.0);
  EXPECT_LT(run.drive.distance_m, 1000.0);
  EXPECT_LT(errors_with_true_params(run).max_position_m,
            quantisation_heading_bound_rad(run, scenario) * largest_radius_m(run) + 0.1);
}

TEST(Simulator, WearShrinksTheTrueCircumferences) {
  Scenario scenario = load_scenario("parking");
  scenario.vehicle.wear_rl_mm = 3.5;
  scenario.vehicle.wear_rr_mm = 2.5;
  const SimulatedDrive drive = simulate(scenario);
  EXPECT_NEAR(drive.true_params.circumference_rl_m, 2 * M_PI * (0.3126 - 0.0035), 1e-12);
  EXPECT_NEAR(drive.true_params.circumference_rr_m, 2 * M_PI * (0.3126 - 0.0025), 1e-12);
  EXPECT_NEAR(drive.nominal_vehicle.circumference_rl_m, 2 * M_PI * 0.3126, 1e-12);
}

// Under-inflation deflects the tyre further under its static load: 1 / pressure times the
// load-sensitivity radius loss (1500 kg, 1.25 of 2.7 m to the front axle: 3405 N per rear wheel).
TEST(Simulator, UnderInflationShrinksTheTrueCircumference) {
  Scenario scenario = load_scenario("parking");
  scenario.vehicle.pressure_rl = 0.75;
  scenario.wheels.output = WheelUnit::kRadians;  // no counter wrap in the angle sums below
  const SimulatedDrive drive = simulate(scenario);
  const double static_load_n = 1500.0 * 9.81 * 1.25 / 2.7 / 2.0;
  const double radius_loss_m = 4e-7 * static_load_n * (1.0 / 0.75 - 1.0);
  EXPECT_NEAR(drive.true_params.circumference_rl_m, 2 * M_PI * (0.3126 - radius_loss_m), 1e-12);
  EXPECT_NEAR(drive.true_params.circumference_rr_m, 2 * M_PI * 0.3126, 1e-12);
  // The wheel turns faster in proportion: its angle over the drive grows by the radius ratio.
  scenario.vehicle.pressure_rl = 1.0;
  const SimulatedDrive inflated = simulate(scenario);
  const auto turned = [](const std::vector<double>& angle) {
    double sum = 0.0;
    for (std::size_t k = 1; k < angle.size(); ++k) sum += std::abs(angle[k] - angle[k - 1]);
    return sum;
  };
  const double ratio = turned(drive.wheel_rl) / turned(inflated.wheel_rl);
  EXPECT_NEAR(ratio, 0.3126 / (0.3126 - radius_loss_m), 2e-4);
}

TEST(Simulator, SensorNoiseHasItsConfiguredSigma) {
  Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  const SimulatedDrive drive = simulate(scenario);
  const PoseStream& truth = drive.truth;
  std::vector<double> gnss_error, heading_error, yaw_rate_error;
  for (std::size_t k = 0; k < drive.gnss_t_s.size(); ++k) {
    const Pose2 pose = *interpolate_pose(truth, drive.gnss_t_s[k]);
    gnss_error.push_back(drive.gnss_a[k] - pose.x());
    gnss_error.push_back(drive.gnss_b[k] - pose.y());
  }
  for (std::size_t k = 0; k < drive.heading.size(); ++k) {
    heading_error.push_back(angle_difference(drive.heading.heading_rad[k],
                                             interpolate_pose(truth, drive.heading.t_s[k])->z()));
  }
  // Yaw rate truth: the central difference of the true yaw where the yaw rate is locally
  // constant (straights and steady arcs; at arc entries the difference would blur a step).
  for (std::size_t k = 1; k + 1 < truth.size(); ++k) {
    const double before = truth.pose[k].z() - truth.pose[k - 1].z();
    const double after = truth.pose[k + 1].z() - truth.pose[k].z();
    if (std::abs(after - before) > 1e-7) continue;
    yaw_rate_error.push_back(drive.imu.wz_radps[k] -
                             (before + after) / (truth.t_s[k + 1] - truth.t_s[k - 1]));
  }
  ASSERT_GT(yaw_rate_error.size(), 10000u);
  // ~50 000 samples: the sample sigma is within 2 % of the configured one.
  EXPECT_NEAR(rms(gnss_error), 3.0, 0.06);
  EXPECT_NEAR(rms(heading_error), 0.15, 0.003);
  EXPECT_NEAR(rms(yaw_rate_error), 0.02, 0.001);
}

TEST(Simulator, DopplerSpeedHasItsConfiguredSigmaAndLeavesThePositionsAlone) {
  const TempLogDir dir;
  Scenario scenario = load_scenario("circuit");
  scenario.route.laps = 1;
  const SimulatedDrive without = simulate(scenario);
  EXPECT_TRUE(without.gnss_speed_mps.empty());
  scenario.gnss.speed_sigma_mps = 0.05;
  const Simulated run = simulate_and_read(scenario, dir);
  EXPECT_EQ(run.drive.gnss_a, without.gnss_a);  // its noise comes from a generator of its own
  const GnssStream& gnss = run.log.gnss;
  ASSERT_EQ(gnss.speed_mps.size(), gnss.size());
  // Truth: the true path's length over 0.2 s around each fix (the realistic car's speed at the
  // rear-axle midpoint, side slip included).
  std::vector<double> error;
  const PoseStream& truth = *run.log.truth;
  for (std::size_t k = 0; k < gnss.size(); ++k) {
    const double t = gnss.t_s[k];
    if (t < truth.t_s.front() + 0.1 || t > truth.t_s.back() - 0.1) continue;
    const Pose2 a = *interpolate_pose(truth, t - 0.1), b = *interpolate_pose(truth, t + 0.1);
    error.push_back(gnss.speed_mps[k] - (b.head<2>() - a.head<2>()).norm() / 0.2);
  }
  ASSERT_GT(error.size(), 5000u);
  EXPECT_NEAR(rms(error), 0.05, 0.003);
  EXPECT_NEAR(std::accumulate(error.begin(), error.end(), 0.0) / static_cast<double>(error.size()),
              0.0, 0.003);
}

// An antenna off the rear axle's centre: each fix is that point of the true pose, and its Doppler
// speed the point's, which a turn to the left slows where the antenna sits on the left.
TEST(Simulator, AnAntennaOffTheAxleReportsItsOwnPositionAndSpeed) {
  Scenario scenario = load_scenario("urban");
  scenario.gnss.sigma_m = 0.0;
  scenario.gnss.speed_sigma_mps = 0.0;
  scenario.gnss.lever_arm_x_m = 1.5;
  scenario.gnss.lever_arm_y_m = 0.5;
  const SimulatedDrive drive = simulate(scenario);
  const PoseStream& truth = drive.truth;
  double largest_position_error = 0.0;
  std::vector<double> speed_error;
  for (std::size_t k = 0; k < drive.gnss_t_s.size(); ++k) {
    const double t = drive.gnss_t_s[k];
    const Pose2 pose = *interpolate_pose(truth, t);
    const double c = std::cos(pose.z()), s = std::sin(pose.z());
    largest_position_error = std::max({largest_position_error,
                                       std::abs(drive.gnss_a[k] - (pose.x() + 1.5 * c - 0.5 * s)),
                                       std::abs(drive.gnss_b[k] - (pose.y() + 1.5 * s + 0.5 * c))});
    if (t < truth.t_s.front() + 0.01 || t > truth.t_s.back() - 0.01) continue;
    // The rigid body's point: v (forward, side slip aside) and the yaw rate's turn of the lever.
    const Pose2 a = *interpolate_pose(truth, t - 0.01), b = *interpolate_pose(truth, t + 0.01);
    const double yaw_rate = (b.z() - a.z()) / 0.02;
    const Eigen::Vector2d velocity = (b.head<2>() - a.head<2>()) / 0.02;
    const Eigen::Vector2d forward(c, s), left(-s, c);
    const Eigen::Vector2d antenna = velocity + yaw_rate * (1.5 * left - 0.5 * forward);
    speed_error.push_back(drive.gnss_speed_mps[k] - antenna.norm());
  }
  EXPECT_LT(largest_position_error, 1e-3);  // the truth as written, interpolated
  ASSERT_GT(speed_error.size(), 1000u);
  EXPECT_LT(rms(speed_error), 0.01);
}

TEST(Simulator, NoiseSeedVariesNoiseOverFixedTruth) {
  Scenario scenario = load_scenario("circuit");  // speed_variation 0.05: the trajectory seed acts
  scenario.route.laps = 1;
  const SimulatedDrive a = simulate(scenario);
  scenario.seeds.noise = 2;
  const SimulatedDrive b = simulate(scenario);
  EXPECT_EQ(a.truth.pose.back(), b.truth.pose.back());
  EXPECT_NE(a.gnss_a[100], b.gnss_a[100]);
  scenario.seeds.noise = 1;
  EXPECT_EQ(simulate(scenario).gnss_a, a.gnss_a);  // reproducible
  scenario.seeds.trajectory = 2;
  EXPECT_NE(simulate(scenario).truth.pose[5000], a.truth.pose[5000]);  // another driver
}

TEST(Simulator, GnssOutagesOutliersAndLatLon) {
  const TempLogDir dir;
  Scenario scenario = load_scenario("urban");
  scenario.gnss.outages = {{60.0, 30.0}};
  scenario.gnss.output_latlon = true;
  scenario.gnss.sigma_m = 0.0;
  scenario.gnss.outlier_rate = 0.02;
  const Simulated run = simulate_and_read(scenario, dir);
  for (double t : run.log.gnss.t_s) EXPECT_FALSE(t >= 60.0 && t < 90.0) << t;
  ASSERT_TRUE(run.log.gnss.origin.has_value());
  // Without white noise every fix is on the path (the reader's ENU origin is the first fix,
  // which is the path start) except the ~2 % outliers of 20-50 m.
  std::size_t outliers = 0;
  for (std::size_t k = 0; k < run.log.gnss.size(); ++k) {
    const Pose2 pose = *interpolate_pose(*run.log.truth, run.log.gnss.t_s[k]);
    const double error = std::hypot(run.log.gnss.x_m[k] - pose.x(), run.log.gnss.y_m[k] - pose.y());
    if (error > 19.9)
      ++outliers;
    else
      EXPECT_LT(error, 0.01);
  }
  EXPECT_NEAR(static_cast<double>(outliers) / static_cast<double>(run.log.gnss.size()), 0.02,
              0.006);
}

// The realistic vehicle with one set of effects on; exact wheel angles, one lap.
TrajectoryErrors realistic_errors(const std::string& name, bool lateral, bool slip, bool radius,
                                  bool transfer,
                                  const std::function<void(Scenario&)>& adjust = nullptr) {
  const TempLogDir dir;
  Scenario scenario = load_scenario(name);
  if (adjust) adjust(scenario);
  scenario.route.laps = 1;
  scenario.wheels.output = WheelUnit::kRadians;
  scenario.dynamics.dynamic_lateral = lateral;
  scenario.dynamics.longitudinal_slip = slip;
  scenario.dynamics.load_dependent_radius = radius;
  scenario.dynamics.load_transfer = transfer;
  return errors_with_true_params(simulate_and_read(scenario, dir));
}

TEST(RealisticSimulator, EveryEffectOffDeadReckonsExactly) {
  // Controller-driven kinematic bicycle, no slip, constant radius: the odometry model holds.
  const TrajectoryErrors errors = realistic_errors("circuit", false, false, false, false);
  EXPECT_LT(errors.max_position_m, 0.01);
  EXPECT_LT(errors.max_heading_rad, 1e-6);
}

TEST(RealisticSimulator, EachEffectAloneMovesDeadReckoningOffTruth) {
  // Side slip: the rear axle slides sideways in corners; the heading stays exact.
  const TrajectoryErrors side_slip = realistic_errors("circuit", true, false, false, false);
  EXPECT_GT(side_slip.mean_position_m, 0.3);
  EXPECT_LT(side_slip.max_heading_rad, 1e-6);
  // Drive and brake slip: wheels turn faster/slower than they roll.
  const TrajectoryErrors slip = realistic_errors("circuit", false, true, false, false);
  EXPECT_GT(slip.max_heading_rad, rad_from_deg(0.1));
  // Load-dependent radius alone changes nothing at static load; with lateral load transfer the
  // outer wheel's smaller radius makes odometry over-estimate every turn.
  EXPECT_LT(realistic_errors("circuit", false, false, true, false).max_position_m, 0.01);
  EXPECT_GT(realistic_errors("circuit", false, false, true, true).max_heading_rad,
            rad_from_deg(1.0));
}

// A front-driven car whose front axle also does all the braking: the rear wheels roll free, so
// with slip the only effect on they still follow the odometry model exactly; driven from the
// rear (or all four) they slip.
TEST(RealisticSimulator, FreeRollingRearWheelsDoNotSlip) {
  const auto drivetrain = [](Drivetrain drive, double brake_front_share) {
    return [=](Scenario& s) {
      s.dynamics.drivetrain = drive;
      s.dynamics.brake_front_share = brake_front_share;
    };
  };
  const TrajectoryErrors front =
      realistic_errors("circuit", false, true, false, false, drivetrain(Drivetrain::kFront, 1.0));
  EXPECT_LT(front.max_position_m, 0.01);
  EXPECT_LT(front.max_heading_rad, 1e-6);
  const TrajectoryErrors all =
      realistic_errors("circuit", false, true, false, false, drivetrain(Drivetrain::kAll, 1.0));
  EXPECT_GT(all.max_heading_rad, rad_from_deg(0.05));
  // Front drive with the usual brake split: only braking slips the rear wheels.
  const TrajectoryErrors braking =
      realistic_errors("circuit", false, true, false, false, drivetrain(Drivetrain::kFront, 0.65));
  const TrajectoryErrors rear =
      realistic_errors("circuit", false, true, false, false, drivetrain(Drivetrain::kRear, 0.65));
  EXPECT_GT(braking.max_heading_rad, 1e-6);
  EXPECT_LT(braking.max_heading_rad, rear.max_heading_rad);
}

// The drive's and the brakes' force follow the driver's command through a first-order lag: over
// one 20 ms wheel sample it moves by at most 1 - exp(-0.02 / tau) of the command's step (18 % at
// tau = 0.1 s), where at once (tau = 0) a brake's onset steps the whole way between two samples.
TEST(RealisticSimulator, TheForceFollowsTheCommandThroughTheActuatorsLag) {
  const auto largest_step_over_range = [](double tau_s) {
    const TempLogDir dir;
    Scenario scenario = load_scenario("circuit");
    scenario.route.laps = 1;
    scenario.wheels.drive_force_sigma_n = 0.0;
    scenario.dynamics.actuator_time_constant_s = tau_s;
    const std::vector<double> force = simulate_and_read(scenario, dir).log.wheels.drive_force_n;
    double step = 0.0;
    for (std::size_t k = 1; k < force.size(); ++k)
      step = std::max(step, std::abs(force[k] - force[k - 1]));
    const auto [low, high] = std::minmax_element(force.begin(), force.end());
    return step / (*high - *low);
  };
  EXPECT_GT(largest_step_over_range(0.0), 0.5);
  EXPECT_LT(largest_step_over_range(0.1), 1.0 - std::exp(-0.02 / 0.1));
}

// Centrifugal growth: the rolling radius grows by k v^2 at the wheel's speed (free-rolling rear
// wheels, so that no slip enters), and not at all with the growth off.
TEST(RealisticSimulator, SteadyRollingRadiusGrowsWithTheSquareOfTheSpeed) {
  VehicleDynamicsConfig c;
  c.drivetrain = Drivetrain::kFront;
  const StaticRearRadii radii{0.31, 0.312};
  for (const double speed : {5.0, 25.0}) {
    EXPECT_NEAR(steady_rolling_radii_m(c, 2.7, 1.6, radii, speed)[0], radii.rl_m, 1e-12);
    c.radius_speed_growth_s2pm2 = 2e-6;
    const auto grown = steady_rolling_radii_m(c, 2.7, 1.6, radii, speed);
    EXPECT_NEAR(grown[0], radii.rl_m * (1.0 + 2e-6 * speed * speed), 1e-12);
    EXPECT_NEAR(grown[1], radii.rr_m * (1.0 + 2e-6 * speed * speed), 1e-12);
    c.radius_speed_growth_s2pm2 = 0.0;
  }
}

TEST(RealisticSimulator, SteadyRollingCircumferenceHasTheDriveSlipOfTheResistance) {
  // Straight at a steady speed a rear-driven car's rear wheels push the drag and rolling
  // resistance: each slips by the inverse magic formula of half that force on its static load,
  // kappa = tan(asin(F / (mu F_z)) / C) / B with B = C_kappa / (C mu); free-rolling wheels do not.
  VehicleDynamicsConfig c;
  const double wheelbase = 2.7, speed = 5.0;
  const StaticRearRadii radii{0.31, 0.312};
  const double resistance = 0.5 * c.air_density_kgpm3 * c.drag_area_m2 * speed * speed +
                            c.rolling_resistance * c.mass_kg * 9.81 * std::tanh(speed / 0.2);
  const double load = c.mass_kg * 9.81 * c.cg_to_front_axle_m / wheelbase / 2.0;
  const double b = c.slip_stiffness_per_load / (c.longitudinal_shape * c.friction);
  const double slip =
      std::tan(std::asin(0.5 * resistance / (c.friction * load)) / c.longitudinal_shape) / b;
  EXPECT_NEAR(slip, 1.37e-3, 2e-5);  // ~2.7 mm of circumference
  const auto rear = steady_rolling_radii_m(c, wheelbase, 1.6, radii, speed);
  EXPECT_NEAR(rear[0], radii.rl_m / (1.0 + slip), 1e-12);
  EXPECT_NEAR(rear[1], radii.rr_m / (1.0 + slip), 1e-12);
  c.drivetrain = Drivetrain::kFront;
  EXPECT_NEAR(steady_rolling_radii_m(c, wheelbase, 1.6, radii, speed)[0], radii.rl_m, 1e-12);

  Scenario scenario = load_scenario("urban");
  const SimulatedDrive drive = simulate(scenario);
  EXPECT_LT(drive.steady_rolling_circumference_m[0], drive.true_params.circumference_rl_m - 2e-3);
  scenario.ideal = true;
  const SimulatedDrive ideal = simulate(scenario);
  EXPECT_EQ(ideal.steady_rolling_circumference_m[1], ideal.true_params.circumference_rr_m);
}

// On a slope the driver holds the speed with the weight's share along it on top of the
// resistance: a rear-driven car's rear wheels slip by the inverse magic formula of half that force
// on their load (which grade moves to the rear as acceleration does, m g sin h / L); downhill the
// force turns to braking, split 35 % to the rear. Straight, at a steady 15 m/s.
TEST(RealisticSimulator, ClimbingSlipsTheDrivenRearWheels) {
  VehicleDynamicsConfig c;
  const double wheelbase = 2.7, speed = 15.0, g = 9.81;
  const StaticRearRadii radii{0.31, 0.31};
  const Path path({{600.0, 0.0, 0.0, 1}}, Pose2::Zero());
  DriverLimits limits;
  limits.max_speed_mps = speed;
  const SpeedProfile profile(path, limits, {});
  const double resistance = 0.5 * c.air_density_kgpm3 * c.drag_area_m2 * speed * speed +
                            c.rolling_resistance * c.mass_kg * g;
  const double b = c.slip_stiffness_per_load / (c.longitudinal_shape * c.friction);
  const double static_load = c.mass_kg * g * c.cg_to_front_axle_m / wheelbase / 2.0;
  const auto expected_rate = [&](double grade) {
    const double sin_pitch = grade / std::sqrt(1.0 + grade * grade);
    const double cos_pitch = 1.0 / std::sqrt(1.0 + grade * grade);
    const double force = resistance + c.mass_kg * g * sin_pitch;
    const double rear_share = force >= 0.0 ? 1.0 : 1.0 - c.brake_front_share;
    const double load = 0.5 * (c.mass_kg * g * cos_pitch * c.cg_to_front_axle_m / wheelbase +
                               c.mass_kg * g * sin_pitch * c.cg_height_m / wheelbase);
    const double slip =
        std::tan(std::asin(0.5 * rear_share * force / (c.friction * load)) / c.longitudinal_shape) /
        b;
    const double radius = radii.rl_m - c.radius_load_sensitivity_m_per_n * (load - static_load);
    return speed * (1.0 + slip) / radius;
  };
  const auto simulated_rate = [&](double grade) {
    const auto motion = simulate_vehicle_dynamics(path, profile, c, wheelbase, 1.6, radii,
                                                  [grade](double) { return grade; });
    return motion->at(0.5 * profile.duration_s()).wheel_rate_rl_radps;
  };
  for (const double grade : {0.0, 0.06, -0.06}) {
    EXPECT_NEAR(simulated_rate(grade) / expected_rate(grade), 1.0, 2e-5) << "grade " << grade;
  }
  // Climbing 6 % takes ~880 N more: several per mille of slip, far above the flat road's.
  EXPECT_GT(expected_rate(0.06) / expected_rate(0.0) - 1.0, 3e-3);
  EXPECT_LT(expected_rate(-0.06), expected_rate(0.0));
}

TEST(ScenarioYaml, DrivetrainIsReadAndChecked) {
  const std::string route = "route: {segments: [{straight: 100}]}\n";
  const Scenario front = parse_scenario(
      route + "vehicle: {dynamics: {drivetrain: front, drive_front_share_all: 0.3}}\n", "s.yaml");
  EXPECT_EQ(front.dynamics.drivetrain, Drivetrain::kFront);
  EXPECT_EQ(front.dynamics.drive_front_share_all, 0.3);
  EXPECT_EQ(load_scenario("urban").dynamics.drivetrain, Drivetrain::kRear);
  try {
    parse_scenario(route + "vehicle:\n  dynamics: {drivetrain: sideways}\n", "s.yaml");
    ADD_FAILURE() << "an unknown drivetrain was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("expected rear, front or all"), std::string::npos)
        << e.what();
  }
}

TEST(ScenarioYaml, TheDriversGripSharingAndPowerAreReadAndWritten) {
  const Scenario read = parse_scenario(
      "route: {segments: [{straight: 100}]}\n"
      "driver: {friction_ellipse: true, max_power_wpkg: 80}\n",
      "s.yaml");
  EXPECT_TRUE(read.driver.friction_ellipse);
  EXPECT_EQ(read.driver.max_power_wpkg, 80.0);
  const Scenario again = parse_scenario(scenario_to_yaml(read), "effective.yaml");
  EXPECT_TRUE(again.driver.friction_ellipse);
  EXPECT_EQ(again.driver.max_power_wpkg, 80.0);
  EXPECT_FALSE(load_scenario("circuit").driver.friction_ellipse);  // each bound on its own
}

TEST(RealisticSimulator, ParkingFollowsItsRouteAndReverses) {
  const TempLogDir dir;
  Scenario ideal = load_scenario("parking");
  ideal.ideal = true;
  const double ideal_distance_m = simulate(ideal).distance_m;
  const Simulated run = simulate_and_read(load_scenario("parking"), dir);
  EXPECT_NEAR(run.drive.distance_m, ideal_distance_m, 0.02 * ideal_distance_m);
  const auto& rl = run.log.wheels.rev_rl;
  EXPECT_LT(*std::min_element(rl.begin(), rl.end()), 0.0);
}

TEST(RealisticSimulator, EffectiveScenarioCarriesTheDynamics) {
  Scenario scenario = load_scenario("urban");
  scenario.dynamics.longitudinal_slip = false;
  scenario.dynamics.mass_kg = 1234.5;
  const Scenario again = parse_scenario(scenario_to_yaml(scenario), "effective.yaml");
  EXPECT_FALSE(again.ideal);
  EXPECT_FALSE(again.dynamics.longitudinal_slip);
  EXPECT_EQ(again.dynamics.mass_kg, 1234.5);
}

TEST(ScenarioYaml, EffectiveConfigurationRoundTrips) {
  Scenario scenario = load_scenario("parking");
  scenario.gnss.outages = {{10.0, 5.0}};
  scenario.vehicle.wear_rl_mm = 1.5;
  const Scenario again = parse_scenario(scenario_to_yaml(scenario), "effective.yaml");
  EXPECT_EQ(scenario_to_yaml(again), scenario_to_yaml(scenario));
  const SimulatedDrive a = simulate(scenario);
  const SimulatedDrive b = simulate(again);
  EXPECT_LT((a.truth.pose.back() - b.truth.pose.back()).norm(), 1e-6);
}

TEST(ScenarioYaml, ErrorsNameFileLineAndKey) {
  try {
    parse_scenario("route:\n  segments:\n    - straight: 10\nsensors:\n  gnss:\n    sigma: 3\n",
                   "s.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "s.yaml:6: 'sensors.gnss.sigma': unknown key");
  }
  try {
    parse_scenario("route:\n  segments:\n    - arc: {radius_m: -5, turn_deg: 90}\n", "s.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().field, "route.segments[0].arc.radius_m");
    EXPECT_EQ(e.location().line, 3u);
  }
  EXPECT_THROW(load_scenario("no-such-scenario"), InputError);
}

}  // namespace
}  // namespace odocal::sim
