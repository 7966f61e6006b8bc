#include "odocal/sim/simulator.hpp"

#include <Eigen/Geometry>
#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>

#include "graded_motion.hpp"
#include "hills.hpp"
#include "odocal/error.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/path_length.hpp"
#include "odocal/sim/simulation_limits.hpp"

namespace odocal::sim {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// Sample times from 0 to duration at `rate_hz`, exact multiples of the period.
std::vector<double> sample_times(double duration_s, double rate_hz) {
  std::vector<double> t;
  const auto count = static_cast<std::size_t>(std::floor(duration_s * rate_hz)) + 1;
  t.reserve(count);
  for (std::size_t k = 0; k < count; ++k) t.push_back(static_cast<double>(k) / rate_hz);
  return t;
}

// The ideal vehicle: exactly on the path at the profile's progress, rolling without slip on
// constant radii. Each rear wheel's signed arc is D -+ (t_R / 2) (yaw - yaw_0), exact for any path.
class IdealMotion : public MotionTruth {
 public:
  IdealMotion(const Path& path, const SpeedProfile& profile, double track_width_m,
              const OdometryParams& truth)
      : path_(path),
        profile_(profile),
        half_track_(0.5 * track_width_m),
        truth_(truth),
        start_yaw_(path.at(0.0).pose.z()) {}
  double duration_s() const override { return profile_.duration_s(); }
  TruthSample at(double t_s) const override {
    const MotionState motion = profile_.at(t_s);
    const PathPoint point = path_.at(motion.s_m);
    const double speed = point.direction * motion.speed_mps;
    const double yaw_rate = point.curvature_1pm * speed;
    const double yaw = point.pose.z() - start_yaw_;
    TruthSample sample;
    sample.pose = point.pose;
    sample.ax_mps2 = point.direction * motion.acc_mps2;
    sample.ay_mps2 = speed * yaw_rate;
    sample.yaw_rate_radps = yaw_rate;
    sample.wheel_angle_rl_rad =
        kTwoPi * (point.signed_distance_m - half_track_ * yaw) / truth_.circumference_rl_m;
    sample.wheel_angle_rr_rad =
        kTwoPi * (point.signed_distance_m + half_track_ * yaw) / truth_.circumference_rr_m;
    sample.wheel_rate_rl_radps =
        kTwoPi * (speed - half_track_ * yaw_rate) / truth_.circumference_rl_m;
    sample.wheel_rate_rr_radps =
        kTwoPi * (speed + half_track_ * yaw_rate) / truth_.circumference_rr_m;
    return sample;
  }

 private:
  const Path& path_;
  const SpeedProfile& profile_;
  double half_track_;
  OdometryParams truth_;
  double start_yaw_;
};

void simulate_wheels(const Scenario& scenario, const MotionTruth& truth, std::mt19937_64& rng,
                     SimulatedDrive& out) {
  const WheelSimConfig& config = scenario.wheels;
  const double nominal_radius_m = scenario.vehicle.tyre_radius_m;
  const double modulus = config.counter_bits > 0 ? std::ldexp(1.0, config.counter_bits) : 0.0;
  // A counter starts at any count and anywhere between two ticks: the fractional part is the
  // encoder phase, which decides where every later count is cut.
  std::uniform_real_distribution<double> start_count(0.0, modulus > 0 ? modulus : 1.0);
  const auto start = [&] {
    const double count = start_count(rng);
    return config.start_phase < 0.0 ? count : std::floor(count) + config.start_phase;
  };
  const double offset_rl = start();
  const double offset_rr = start();
  const auto ticks = [&](double angle_rad, double offset) {
    double count = std::floor(offset + angle_rad / kTwoPi * config.ticks_per_rev);
    if (modulus > 0) count -= modulus * std::floor(count / modulus);
    return count;
  };

  out.wheel_unit = config.output;
  for (double t : sample_times(truth.duration_s(), config.rate_hz)) {
    const TruthSample sample = truth.at(t);
    double rl = 0.0, rr = 0.0;
    switch (config.output) {
      case WheelUnit::kTicks:
        rl = ticks(sample.wheel_angle_rl_rad, offset_rl);
        rr = ticks(sample.wheel_angle_rr_rad, offset_rr);
        break;
      case WheelUnit::kRadians:
        rl = sample.wheel_angle_rl_rad;
        rr = sample.wheel_angle_rr_rad;
        break;
      case WheelUnit::kRadiansPerSecond:
        rl = sample.wheel_rate_rl_radps + config.rate_bias_rl_radps;
        rr = sample.wheel_rate_rr_radps + config.rate_bias_rr_radps;
        break;
      case WheelUnit::kMetresPerSecond:  // the vehicle converts with its nominal radius
        rl = (sample.wheel_rate_rl_radps + config.rate_bias_rl_radps) * nominal_radius_m;
        rr = (sample.wheel_rate_rr_radps + config.rate_bias_rr_radps) * nominal_radius_m;
        break;
    }
    out.wheel_t_s.push_back(t);
    out.wheel_rl.push_back(rl);
    out.wheel_rr.push_back(rr);
    out.truth.t_s.push_back(t);
    out.truth.pose.push_back(sample.pose);
  }
  out.distance_m = path_length_m(out.truth.pose);
}

// The tyres' force as the car's bus reports it, at the wheels' sample times, from a generator of
// its own (every other sensor keeps its noise).
void simulate_drive_force(const Scenario& scenario, const MotionTruth& truth, SimulatedDrive& out) {
  const WheelSimConfig& config = scenario.wheels;
  if (config.drive_force_sigma_n < 0.0) return;
  if (scenario.ideal) {
    throw InputError({"scenario", 0, "sensors.wheels.drive_force_sigma_n"},
                     "the ideal vehicle has no tyre forces to report (set ideal: false)");
  }
  std::seed_seq seeds{scenario.seeds.noise, std::uint64_t{0xf04ce}};
  std::mt19937_64 rng(seeds);
  std::normal_distribution<double> unit(0.0, 1.0);
  out.wheel_drive_force_n.reserve(out.wheel_t_s.size());
  for (const double t : out.wheel_t_s) {
    out.wheel_drive_force_n.push_back(config.drive_force_scale * truth.at(t).longitudinal_force_n +
                                      config.drive_force_sigma_n * unit(rng));
  }
}

// Where the antenna at `lever` (ahead, left of the rear axle's centre) is at `pose`.
Eigen::Vector2d antenna_at(const Pose2& pose, const Eigen::Vector2d& lever) {
  return pose.head<2>() + Eigen::Rotation2Dd(pose.z()) * lever;
}

// The antenna's horizontal speed over ground at t (central difference of the truth), the side
// slip and its turn about the axle's centre included.
double ground_speed_mps(const MotionTruth& truth, double t_s, const Eigen::Vector2d& lever) {
  constexpr double kHalfStep = 1e-3;
  const double from = std::max(t_s - kHalfStep, 0.0);
  const double to = std::min(t_s + kHalfStep, truth.duration_s());
  if (to <= from) return 0.0;
  return (antenna_at(truth.at(to).pose, lever) - antenna_at(truth.at(from).pose, lever)).norm() /
         (to - from);
}

void simulate_gnss(const GnssSimConfig& config, bool altitude, const MotionTruth& truth,
                   std::mt19937_64& rng, std::mt19937_64& speed_rng, SimulatedDrive& out) {
  const double altitude_sigma_m =
      config.altitude_sigma_m >= 0.0 ? config.altitude_sigma_m : 1.5 * config.sigma_m;
  std::normal_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  // A distribution of its own: one draws its normals in pairs and keeps the second.
  std::normal_distribution<double> speed_unit(0.0, 1.0);
  const GeographicLib::LocalCartesian enu(config.origin.latitude_deg, config.origin.longitude_deg,
                                          config.origin.altitude_m);
  const double period_s = 1.0 / config.rate_hz;
  const double decay =
      config.gauss_markov_tau_s > 0 ? std::exp(-period_s / config.gauss_markov_tau_s) : 0.0;
  const double drive_sigma = config.gauss_markov_sigma_m * std::sqrt(1.0 - decay * decay);
  Eigen::Vector2d coloured(config.gauss_markov_sigma_m * unit(rng),
                           config.gauss_markov_sigma_m * unit(rng));
  const Eigen::Vector2d lever(config.lever_arm_x_m, config.lever_arm_y_m);
  out.gnss_latlon = config.output_latlon;
  out.gnss_sigma_m = std::hypot(config.sigma_m, config.gauss_markov_sigma_m);
  for (double t : sample_times(truth.duration_s(), config.rate_hz)) {
    // Every draw happens for every epoch, so an outage does not shift later noise.
    coloured = decay * coloured + drive_sigma * Eigen::Vector2d(unit(rng), unit(rng));
    Eigen::Vector2d error = coloured + config.sigma_m * Eigen::Vector2d(unit(rng), unit(rng));
    const bool outlier = uniform(rng) < config.outlier_rate;
    const double outlier_size =
        config.outlier_min_m + (config.outlier_max_m - config.outlier_min_m) * uniform(rng);
    const double outlier_angle = kTwoPi * uniform(rng);
    // Drawn only on hills: flat logs keep their noise sequence.
    const double altitude_noise = altitude ? altitude_sigma_m * unit(rng) : 0.0;
    const double speed_noise =
        config.speed_sigma_mps > 0.0 ? config.speed_sigma_mps * speed_unit(speed_rng) : 0.0;
    if (outlier)
      error += outlier_size * Eigen::Vector2d(std::cos(outlier_angle), std::sin(outlier_angle));

    bool in_outage = false;
    for (const Outage& outage : config.outages) {
      in_outage = in_outage || (t >= outage.start_s && t < outage.start_s + outage.duration_s);
    }
    if (in_outage || t < config.latency_s) continue;
    const TruthSample sample = truth.at(t - config.latency_s);
    const Eigen::Vector2d antenna = antenna_at(sample.pose, lever);
    const double x = antenna.x() + error.x();
    const double y = antenna.y() + error.y();
    const double up = altitude ? sample.altitude_m + altitude_noise : 0.0;
    out.gnss_t_s.push_back(t);
    if (config.speed_sigma_mps >= 0.0) {
      out.gnss_speed_mps.push_back(
          std::max(ground_speed_mps(truth, t - config.latency_s, lever) + speed_noise, 0.0));
    }
    if (config.output_latlon) {
      double lat = 0, lon = 0, alt = 0;
      enu.Reverse(x, y, up, lat, lon, alt);
      out.gnss_a.push_back(lat);
      out.gnss_b.push_back(lon);
      if (altitude) out.gnss_alt.push_back(alt);
    } else {
      if (altitude) out.gnss_alt.push_back(up);
      out.gnss_a.push_back(x);
      out.gnss_b.push_back(y);
    }
  }
}

void simulate_imu_and_heading(const Scenario& scenario, const MotionTruth& truth,
                              std::mt19937_64& rng, SimulatedDrive& out) {
  std::normal_distribution<double> unit(0.0, 1.0);
  const double mount_x = scenario.imu.mount_x_m, mount_y = scenario.imu.mount_y_m;
  for (double t : sample_times(truth.duration_s(), scenario.imu.rate_hz)) {
    const TruthSample sample = truth.at(t);
    // An IMU mounted r from the point the truth's accelerations are of reads dw/dt x r and
    // w x (w x r) = -w^2 r beside them (rigid body).
    double mount_ax = 0.0, mount_ay = 0.0;
    if (mount_x != 0.0 || mount_y != 0.0) {
      constexpr double kStepS = 1e-3;
      const double before = std::max(t - kStepS, 0.0);
      const double after = std::min(t + kStepS, truth.duration_s());
      const double w = sample.yaw_rate_radps;
      const double w_dot =
          (truth.at(after).yaw_rate_radps - truth.at(before).yaw_rate_radps) / (after - before);
      mount_ax = -w_dot * mount_y - w * w * mount_x;
      mount_ay = w_dot * mount_x - w * w * mount_y;
    }
    out.imu.t_s.push_back(t);
    out.imu.ax_mps2.push_back(sample.ax_mps2 + mount_ax + scenario.imu.acc_sigma_mps2 * unit(rng));
    out.imu.ay_mps2.push_back(sample.ay_mps2 + mount_ay + scenario.imu.acc_sigma_mps2 * unit(rng));
    out.imu.wz_radps.push_back(sample.yaw_rate_radps + scenario.imu.gyro_bias_radps +
                               scenario.imu.yaw_rate_sigma_radps * unit(rng));
  }
  for (double t : sample_times(truth.duration_s(), scenario.heading.rate_hz)) {
    out.heading.t_s.push_back(t);
    out.heading.heading_rad.push_back(wrap_angle(truth.at(t).pose.z() + scenario.heading.bias_rad +
                                                 scenario.heading.sigma_rad * unit(rng)));
  }
}

}  // namespace

Path route_path(const Scenario& scenario) {
  std::vector<PathSegment> segments;
  for (int lap = 0; lap < scenario.route.laps * scenario.route.repeat; ++lap) {
    for (const RouteSegment& segment : scenario.route.segments)
      segments.push_back(segment.geometry);
  }
  return Path(std::move(segments), scenario.route.start);
}

SimulatedDrive simulate(const Scenario& scenario) {
  check_route_size(scenario);
  const Path path = route_path(scenario);
  std::vector<Stop> stops;
  double s = 0.0;
  for (std::size_t i = 0; i < path.segments().size(); ++i) {
    s += path.segments()[i].length_m;
    const RouteSegment& segment = scenario.route.segments[i % scenario.route.segments.size()];
    if (segment.stop_dwell_s > 0) stops.push_back({s, segment.stop_dwell_s});
  }
  std::mt19937_64 trajectory_rng(scenario.seeds.trajectory);
  std::uniform_real_distribution<double> variation(1.0 - scenario.speed_variation, 1.0);
  std::vector<double> speed_scale(path.segments().size());
  for (double& scale : speed_scale) scale = variation(trajectory_rng);
  const SpeedProfile profile(path, scenario.driver, stops, speed_scale);
  check_drive_size(scenario, profile.duration_s());

  SimulatedDrive out;
  const double nominal_c = kTwoPi * scenario.vehicle.tyre_radius_m;
  out.nominal_vehicle.track_width_m = scenario.vehicle.track_width_m;
  out.nominal_vehicle.circumference_rl_m = nominal_c;
  out.nominal_vehicle.circumference_rr_m = nominal_c;
  out.nominal_vehicle.wheelbase_m = scenario.vehicle.wheelbase_m;
  // What its owner knows of the car; the body's numbers are left to the defaults (a calibration
  // is not told the simulated car's load geometry).
  out.nominal_vehicle.body.drivetrain = scenario.dynamics.drivetrain;
  // Where its IMU is mounted, as an owner knows: `imu.mount` from the point whose motion each
  // mode reads (realistic: the centre of gravity, where the dynamics' accelerations are the
  // body's; ideal: the rear axle, unstated there when the mount is zero).
  const Eigen::Vector2d mount(scenario.imu.mount_x_m, scenario.imu.mount_y_m);
  if (!scenario.ideal) {
    out.nominal_vehicle.imu_position_m =
        Eigen::Vector2d(scenario.vehicle.wheelbase_m - scenario.dynamics.cg_to_front_axle_m, 0.0) +
        mount;
  } else if (!mount.isZero()) {
    out.nominal_vehicle.imu_position_m = mount;
  }
  if (scenario.gnss.lever_arm_stated) {
    out.nominal_vehicle.gnss_position_m =
        Eigen::Vector2d(scenario.gnss.lever_arm_x_m, scenario.gnss.lever_arm_y_m);
  }
  if (scenario.wheels.output == WheelUnit::kTicks) {
    out.nominal_vehicle.ticks_per_rev = scenario.wheels.ticks_per_rev;
    if (scenario.wheels.counter_bits > 0)
      out.nominal_vehicle.counter_bits = scenario.wheels.counter_bits;
  }
  // The wheels turn as if the track were the effective one: the truth a calibration should find.
  const double track_m = scenario.vehicle.effective_track_width_m > 0.0
                             ? scenario.vehicle.effective_track_width_m
                             : scenario.vehicle.track_width_m;
  // Under-inflation deflects the tyre further under its static load: that radius is lost too.
  const double radius_per_pressure_m =
      scenario.dynamics.radius_load_sensitivity_m_per_n *
      static_rear_wheel_load_n(scenario.dynamics, scenario.vehicle.wheelbase_m);
  const auto static_radius_m = [&](double wear_mm, double pressure) {
    return scenario.vehicle.tyre_radius_m - 1e-3 * wear_mm -
           radius_per_pressure_m * (1.0 / pressure - 1.0);
  };
  out.true_params = {
      kTwoPi * static_radius_m(scenario.vehicle.wear_rl_mm, scenario.vehicle.pressure_rl),
      kTwoPi * static_radius_m(scenario.vehicle.wear_rr_mm, scenario.vehicle.pressure_rr), track_m};

  // One generator per sensor, each seeded from the noise seed: changing one sensor's rate never
  // changes another sensor's noise.
  std::seed_seq seeds{scenario.seeds.noise, std::uint64_t{0x0d0ca1}};
  std::array<std::uint64_t, 4> sensor_seeds{};
  seeds.generate(sensor_seeds.begin(), sensor_seeds.end());
  std::mt19937_64 wheel_rng(sensor_seeds[0]), gnss_rng(sensor_seeds[1]), imu_rng(sensor_seeds[2]),
      speed_rng(sensor_seeds[3]);
  out.steady_rolling_circumference_m = {out.true_params.circumference_rl_m,
                                        out.true_params.circumference_rr_m};
  std::unique_ptr<MotionTruth> truth;
  if (scenario.ideal) {
    truth = std::make_unique<IdealMotion>(path, profile, track_m, out.true_params);
  } else {
    const StaticRearRadii radii{out.true_params.circumference_rl_m / kTwoPi,
                                out.true_params.circumference_rr_m / kTwoPi,
                                scenario.vehicle.pressure_rl, scenario.vehicle.pressure_rr};
    std::function<double(double)> grade;
    if (scenario.route.terrain.max_grade > 0.0) {
      grade = [hills = Hills(scenario.route.terrain, path.length_m() / scenario.route.laps)](
                  double s_m) { return hills.grade(s_m); };
    }
    truth = simulate_vehicle_dynamics(path, profile, scenario.dynamics,
                                      scenario.vehicle.wheelbase_m, track_m, radii, grade);
    const std::array<double, 2> rolling =
        steady_rolling_radii_m(scenario.dynamics, scenario.vehicle.wheelbase_m, track_m, radii,
                               out.steady_rolling_speed_mps);
    out.steady_rolling_circumference_m = {kTwoPi * rolling[0], kTwoPi * rolling[1]};
  }
  if (scenario.route.terrain.max_grade > 0.0) {
    const double lap_length_m = path.length_m() / scenario.route.laps;
    truth = std::make_unique<GradedMotion>(std::move(truth), scenario.route.terrain, lap_length_m);
  }
  simulate_wheels(scenario, *truth, wheel_rng, out);
  simulate_drive_force(scenario, *truth, out);
  const bool hills = scenario.route.terrain.max_grade > 0.0;
  using Altitude = GnssSimConfig::Altitude;
  const bool altitude = scenario.gnss.altitude == Altitude::kAlways ||
                        (scenario.gnss.altitude == Altitude::kAuto && hills);
  simulate_gnss(scenario.gnss, altitude, *truth, gnss_rng, speed_rng, out);
  if (out.gnss_t_s.size() < 2) {
    throw InputError({"scenario", 0, "sensors.gnss.outages"},
                     "the outages leave fewer than 2 GNSS fixes in the whole drive");
  }
  simulate_imu_and_heading(scenario, *truth, imu_rng, out);
  return out;
}

}  // namespace odocal::sim
