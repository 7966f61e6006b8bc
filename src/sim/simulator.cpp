#include "odocal/sim/simulator.hpp"

#include <GeographicLib/LocalCartesian.hpp>
#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include "odocal/error.hpp"
#include "odocal/model/angle.hpp"

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

// Kinematic truth of the reference point at time t.
struct KinematicState {
  PathPoint point;
  double signed_speed_mps;
  double signed_acc_mps2;
};

class KinematicDrive {
 public:
  KinematicDrive(const Path& path, const SpeedProfile& profile) : path_(path), profile_(profile) {}
  KinematicState at(double t_s) const {
    const MotionState motion = profile_.at(t_s);
    const PathPoint point = path_.at(motion.s_m);
    return {point, point.direction * motion.speed_mps, point.direction * motion.acc_mps2};
  }

 private:
  const Path& path_;
  const SpeedProfile& profile_;
};

void simulate_wheels(const Scenario& scenario, const KinematicDrive& drive, double duration_s,
                     std::mt19937_64& rng, SimulatedDrive& out) {
  const WheelSimConfig& config = scenario.wheels;
  const double half_track = 0.5 * scenario.vehicle.track_width_m;
  const double nominal_c = out.nominal_vehicle.circumference_rl_m;
  const double modulus = config.counter_bits > 0 ? std::ldexp(1.0, config.counter_bits) : 0.0;
  std::uniform_real_distribution<double> start_count(0.0, modulus > 0 ? modulus : 1.0);
  const double offset_rl = std::floor(start_count(rng));
  const double offset_rr = std::floor(start_count(rng));
  const Pose2 start = drive.at(0.0).point.pose;

  out.wheel_unit = config.output;
  for (double t : sample_times(duration_s, config.rate_hz)) {
    const KinematicState state = drive.at(t);
    const double yaw = state.point.pose.z() - start.z();
    // Rolling without slip: each wheel's signed arc is D -+ (t_R / 2) yaw.
    const double arc_rl = state.point.signed_distance_m - half_track * yaw;
    const double arc_rr = state.point.signed_distance_m + half_track * yaw;
    const double yaw_rate = state.point.curvature_1pm * state.signed_speed_mps;
    const double speed_rl = state.signed_speed_mps - half_track * yaw_rate;
    const double speed_rr = state.signed_speed_mps + half_track * yaw_rate;
    const double c_rl = out.true_params.circumference_rl_m;
    const double c_rr = out.true_params.circumference_rr_m;
    double rl = 0.0, rr = 0.0;
    switch (config.output) {
      case WheelUnit::kTicks: {
        rl = offset_rl + std::floor(arc_rl / c_rl * config.ticks_per_rev);
        rr = offset_rr + std::floor(arc_rr / c_rr * config.ticks_per_rev);
        if (modulus > 0) {
          rl = rl - modulus * std::floor(rl / modulus);
          rr = rr - modulus * std::floor(rr / modulus);
        }
        break;
      }
      case WheelUnit::kRadians:
        rl = arc_rl / c_rl * kTwoPi;
        rr = arc_rr / c_rr * kTwoPi;
        break;
      case WheelUnit::kRadiansPerSecond:
        rl = speed_rl / c_rl * kTwoPi;
        rr = speed_rr / c_rr * kTwoPi;
        break;
      case WheelUnit::kMetresPerSecond:  // the vehicle converts with its nominal circumference
        rl = speed_rl / c_rl * nominal_c;
        rr = speed_rr / c_rr * nominal_c;
        break;
    }
    out.wheel_t_s.push_back(t);
    out.wheel_rl.push_back(rl);
    out.wheel_rr.push_back(rr);
    out.truth.t_s.push_back(t);
    out.truth.pose.push_back(state.point.pose);
  }
  out.distance_m = 0.0;
  for (std::size_t k = 1; k < out.truth.size(); ++k) {
    out.distance_m += (out.truth.pose[k].head<2>() - out.truth.pose[k - 1].head<2>()).norm();
  }
}

void simulate_gnss(const GnssSimConfig& config, const KinematicDrive& drive, double duration_s,
                   std::mt19937_64& rng, SimulatedDrive& out) {
  std::normal_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const GeographicLib::LocalCartesian enu(config.origin.latitude_deg, config.origin.longitude_deg,
                                          config.origin.altitude_m);
  const double period_s = 1.0 / config.rate_hz;
  const double decay =
      config.gauss_markov_tau_s > 0 ? std::exp(-period_s / config.gauss_markov_tau_s) : 0.0;
  const double drive_sigma = config.gauss_markov_sigma_m * std::sqrt(1.0 - decay * decay);
  Eigen::Vector2d coloured(config.gauss_markov_sigma_m * unit(rng),
                           config.gauss_markov_sigma_m * unit(rng));
  out.gnss_latlon = config.output_latlon;
  out.gnss_sigma_m = std::hypot(config.sigma_m, config.gauss_markov_sigma_m);
  for (double t : sample_times(duration_s, config.rate_hz)) {
    // Every draw happens for every epoch, so an outage does not shift later noise.
    coloured = decay * coloured + drive_sigma * Eigen::Vector2d(unit(rng), unit(rng));
    Eigen::Vector2d error = coloured + config.sigma_m * Eigen::Vector2d(unit(rng), unit(rng));
    const bool outlier = uniform(rng) < config.outlier_rate;
    const double outlier_size =
        config.outlier_min_m + (config.outlier_max_m - config.outlier_min_m) * uniform(rng);
    const double outlier_angle = kTwoPi * uniform(rng);
    if (outlier)
      error += outlier_size * Eigen::Vector2d(std::cos(outlier_angle), std::sin(outlier_angle));

    bool in_outage = false;
    for (const Outage& outage : config.outages) {
      in_outage = in_outage || (t >= outage.start_s && t < outage.start_s + outage.duration_s);
    }
    if (in_outage || t < config.latency_s) continue;
    const Pose2 pose = drive.at(t - config.latency_s).point.pose;
    const double x = pose.x() + error.x();
    const double y = pose.y() + error.y();
    out.gnss_t_s.push_back(t);
    if (config.output_latlon) {
      double lat = 0, lon = 0, alt = 0;
      enu.Reverse(x, y, 0.0, lat, lon, alt);
      out.gnss_a.push_back(lat);
      out.gnss_b.push_back(lon);
    } else {
      out.gnss_a.push_back(x);
      out.gnss_b.push_back(y);
    }
  }
}

void simulate_imu_and_heading(const Scenario& scenario, const KinematicDrive& drive,
                              double duration_s, std::mt19937_64& rng, SimulatedDrive& out) {
  std::normal_distribution<double> unit(0.0, 1.0);
  for (double t : sample_times(duration_s, scenario.imu.rate_hz)) {
    const KinematicState state = drive.at(t);
    const double yaw_rate = state.point.curvature_1pm * state.signed_speed_mps;
    out.imu.t_s.push_back(t);
    out.imu.ax_mps2.push_back(state.signed_acc_mps2 + scenario.imu.acc_sigma_mps2 * unit(rng));
    out.imu.ay_mps2.push_back(state.signed_speed_mps * yaw_rate +
                              scenario.imu.acc_sigma_mps2 * unit(rng));
    out.imu.wz_radps.push_back(yaw_rate + scenario.imu.gyro_bias_radps +
                               scenario.imu.yaw_rate_sigma_radps * unit(rng));
  }
  for (double t : sample_times(duration_s, scenario.heading.rate_hz)) {
    const double yaw = drive.at(t).point.pose.z();
    out.heading.t_s.push_back(t);
    out.heading.heading_rad.push_back(
        wrap_angle(yaw + scenario.heading.bias_rad + scenario.heading.sigma_rad * unit(rng)));
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
  if (!scenario.ideal) {
    throw Error(
        "the dynamic vehicle model (slip, load-dependent radius) is not built yet: "
        "simulate with --ideal");
  }
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
  const KinematicDrive drive(path, profile);

  SimulatedDrive out;
  const double nominal_c = kTwoPi * scenario.vehicle.tyre_radius_m;
  out.nominal_vehicle.track_width_m = scenario.vehicle.track_width_m;
  out.nominal_vehicle.circumference_rl_m = nominal_c;
  out.nominal_vehicle.circumference_rr_m = nominal_c;
  out.nominal_vehicle.wheelbase_m = scenario.vehicle.wheelbase_m;
  if (scenario.wheels.output == WheelUnit::kTicks) {
    out.nominal_vehicle.ticks_per_rev = scenario.wheels.ticks_per_rev;
    if (scenario.wheels.counter_bits > 0)
      out.nominal_vehicle.counter_bits = scenario.wheels.counter_bits;
  }
  out.true_params = {kTwoPi * (scenario.vehicle.tyre_radius_m - 1e-3 * scenario.vehicle.wear_rl_mm),
                     kTwoPi * (scenario.vehicle.tyre_radius_m - 1e-3 * scenario.vehicle.wear_rr_mm),
                     scenario.vehicle.track_width_m};

  // One generator per sensor, each seeded from the noise seed: changing one sensor's rate never
  // changes another sensor's noise.
  std::seed_seq seeds{scenario.seeds.noise, std::uint64_t{0x0d0ca1}};
  std::array<std::uint64_t, 4> sensor_seeds{};
  seeds.generate(sensor_seeds.begin(), sensor_seeds.end());
  std::mt19937_64 wheel_rng(sensor_seeds[0]), gnss_rng(sensor_seeds[1]), imu_rng(sensor_seeds[2]);
  const double duration_s = profile.duration_s();
  simulate_wheels(scenario, drive, duration_s, wheel_rng, out);
  simulate_gnss(scenario.gnss, drive, duration_s, gnss_rng, out);
  simulate_imu_and_heading(scenario, drive, duration_s, imu_rng, out);
  return out;
}

}  // namespace odocal::sim
