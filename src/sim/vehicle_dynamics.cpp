#include "odocal/sim/vehicle_dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "hills.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/gravity.hpp"

namespace odocal::sim {
namespace {

// CG state: position, yaw, body velocities, yaw rate, rear wheel angles.
struct State {
  double x, y, yaw, vx, vy, r, angle_rl, angle_rr;
};
struct Derivative {
  double x, y, yaw, vx, vy, r, angle_rl, angle_rr;
};
State step_state(const State& s, const Derivative& d, double h) {
  return {s.x + h * d.x,   s.y + h * d.y, s.yaw + h * d.yaw,           s.vx + h * d.vx,
          s.vy + h * d.vy, s.r + h * d.r, s.angle_rl + h * d.angle_rl, s.angle_rr + h * d.angle_rr};
}

// Controls held over a control period.
struct Controls {
  double steer_rad;
  double force_n;  // total longitudinal tyre force (signed, body x), after the actuators' lag
  Pitch pitch;     // of the road under the car: climbing takes m g sin(pitch) of the force
};

class Vehicle {
 public:
  Vehicle(const VehicleDynamicsConfig& c, double wheelbase_m, double track_width_m,
          const StaticRearRadii& radii)
      : c_(c),
        L_(wheelbase_m),
        a_(c.cg_to_front_axle_m),
        b_(wheelbase_m - c.cg_to_front_axle_m),
        t_(track_width_m),
        radii_(radii) {}

  double rear_offset_m() const { return b_; }
  bool kinematic(const State& s) const {
    return !c_.dynamic_lateral || std::abs(s.vx) < c_.kinematic_below_mps;
  }

  // Resistance forces opposing motion (smoothed through standstill).
  double resistance_n(double vx) const {
    return 0.5 * c_.air_density_kgpm3 * c_.drag_area_m2 * vx * std::abs(vx) +
           c_.rolling_resistance * c_.mass_kg * kGravityMps2 * std::tanh(vx / 0.2);
  }

  Derivative derivative(const State& s, const Controls& u, double* ay_out = nullptr) const {
    Derivative d{};
    double vy = s.vy, r = s.r;
    if (kinematic(s)) {  // rear axle rolls without side slip
      r = s.vx * std::tan(u.steer_rad) / L_;
      vy = b_ * r;
    }
    const double cos_yaw = std::cos(s.yaw), sin_yaw = std::sin(s.yaw);
    d.x = s.vx * cos_yaw - vy * sin_yaw;
    d.y = s.vx * sin_yaw + vy * cos_yaw;
    d.yaw = r;

    // The longitudinal force splits between the axles: the drive by the drivetrain, the brakes by
    // their split. The front axle's force acts along its steered wheels.
    const double front_share = u.force_n >= 0.0 ? drive_front_share() : c_.brake_front_share;
    const double drive_n = (1.0 - front_share) * u.force_n;  // rear axle
    const double front_brake_n = front_share * u.force_n;
    // On a slope the ground's force also holds the weight's component along it: that moves load
    // to the rear as acceleration does.
    const Pitch& pitch = u.pitch;
    const double slope_n = c_.mass_kg * kGravityMps2 * pitch.sin;
    // Load moves with the body's own acceleration: the drive's less the resistance's and, in a
    // turn, the front tyres' cornering drag. That drag hangs on the loads, so the two settle in
    // a fixed point; a few passes do (the drag's share of a load change is sin(delta) small).
    const double weight_front_n = c_.mass_kg * kGravityMps2 * pitch.cos * b_ / L_;
    const double weight_rear_n = c_.mass_kg * kGravityMps2 * pitch.cos * a_ / L_;
    double specific_force_x = (u.force_n - resistance_n(s.vx)) / c_.mass_kg;
    double load_front = 0.0, load_rear = 0.0;
    const auto share_load = [&] {
      const double transfer_x =
          c_.load_transfer ? c_.mass_kg * specific_force_x * c_.cg_height_m / L_ : 0.0;
      load_front = weight_front_n - transfer_x;
      load_rear = weight_rear_n + transfer_x;
    };
    share_load();
    double ay = s.vx * r;
    if (kinematic(s)) {
      d.vx = (u.force_n - resistance_n(s.vx) - slope_n) / c_.mass_kg;
    } else {
      const double alpha_front = u.steer_rad - std::atan2(s.vy + a_ * s.r, s.vx);
      const double alpha_rear = -std::atan2(s.vy - b_ * s.r, s.vx);
      const double cos_d = std::cos(u.steer_rad), sin_d = std::sin(u.steer_rad);
      double fy_front = 0.0, fy_rear = 0.0;
      constexpr int kLoadPasses = 3;
      for (int pass = 0; pass < kLoadPasses; ++pass) {
        if (pass > 0) share_load();
        fy_front = lateral_force(alpha_front, load_front, c_.cornering_stiffness_per_load_front);
        fy_rear = lateral_force(alpha_rear, load_rear, c_.cornering_stiffness_per_load_rear);
        specific_force_x =
            (drive_n + front_brake_n * cos_d - fy_front * sin_d - resistance_n(s.vx)) / c_.mass_kg;
      }
      d.vx = specific_force_x - slope_n / c_.mass_kg + s.r * s.vy;
      d.vy = (fy_rear + fy_front * cos_d + front_brake_n * sin_d) / c_.mass_kg - s.r * s.vx;
      d.r = (a_ * (fy_front * cos_d + front_brake_n * sin_d) - b_ * fy_rear) / c_.yaw_inertia_kgm2;
      ay = d.vy + s.r * s.vx;
    }
    if (ay_out != nullptr) *ay_out = ay;

    // Rear wheels: contact-point speed, slip from the tyre model, load-dependent radius.
    const double transfer_y =
        c_.load_transfer ? (1.0 - c_.front_roll_share) * c_.mass_kg * ay * c_.cg_height_m / t_
                         : 0.0;
    const double static_wheel_load = static_rear_wheel_load_n(c_, L_);
    const double load_rl =
        0.5 * load_rear - transfer_y;  // a left turn (ay > 0) loads the right wheel
    const double load_rr = 0.5 * load_rear + transfer_y;
    d.angle_rl = wheel_rate(s.vx - r * t_ / 2.0, 0.5 * drive_n, load_rl, static_wheel_load,
                            radii_.rl_m, radii_.pressure_rl);
    d.angle_rr = wheel_rate(s.vx + r * t_ / 2.0, 0.5 * drive_n, load_rr, static_wheel_load,
                            radii_.rr_m, radii_.pressure_rr);
    return d;
  }

  double drive_front_share() const {
    switch (c_.drivetrain) {
      case Drivetrain::kFront:
        return 1.0;
      case Drivetrain::kAll:
        return c_.drive_front_share_all;
      case Drivetrain::kRear:
        break;
    }
    return 0.0;
  }

  // A rear wheel's ground distance per radian rolling straight at a steady speed: the drive
  // balances the resistance, the load is static.
  double steady_rolling_radius_m(double speed_mps, bool left) const {
    const double drive_n = (1.0 - drive_front_share()) * resistance_n(speed_mps);
    const double load_n = static_rear_wheel_load_n(c_, L_);
    return speed_mps / wheel_rate(speed_mps, 0.5 * drive_n, load_n, load_n,
                                  left ? radii_.rl_m : radii_.rr_m,
                                  left ? radii_.pressure_rl : radii_.pressure_rr);
  }

  double wheel_radius(double load_n, double static_load_n, double static_radius_m,
                      double pressure) const {
    return c_.load_dependent_radius ? static_radius_m - c_.radius_load_sensitivity_m_per_n /
                                                            pressure * (load_n - static_load_n)
                                    : static_radius_m;
  }

 private:
  double lateral_force(double alpha, double load_n, double stiffness_per_load) const {
    const double B = stiffness_per_load / (c_.lateral_shape * c_.friction);
    return c_.friction * load_n * std::sin(c_.lateral_shape * std::atan(B * alpha));
  }

  // Inverse magic formula: the longitudinal slip that transmits force_n on this load.
  double longitudinal_slip(double force_n, double load_n) const {
    if (!c_.longitudinal_slip || load_n <= 0.0) return 0.0;
    const double ratio = std::clamp(force_n / (c_.friction * load_n), -0.99, 0.99);
    const double B = c_.slip_stiffness_per_load / (c_.longitudinal_shape * c_.friction);
    return std::tan(std::asin(ratio) / c_.longitudinal_shape) / B;
  }

  double wheel_rate(double contact_speed, double force_n, double load_n, double static_load_n,
                    double static_radius_m, double pressure) const {
    const double slip = longitudinal_slip(force_n, load_n);
    const double growth = 1.0 + c_.radius_speed_growth_s2pm2 * contact_speed * contact_speed;
    return contact_speed * (1.0 + slip) /
           (wheel_radius(load_n, static_load_n, static_radius_m, pressure) * growth);
  }

  const VehicleDynamicsConfig& c_;
  double L_, a_, b_, t_;
  StaticRearRadii radii_;
};

class RecordedMotion : public MotionTruth {
 public:
  explicit RecordedMotion(double step_s) : step_s_(step_s) {}
  void add(const TruthSample& sample) { samples_.push_back(sample); }
  double duration_s() const override { return step_s_ * static_cast<double>(samples_.size() - 1); }
  TruthSample at(double t_s) const override {
    const double position =
        std::clamp(t_s / step_s_, 0.0, static_cast<double>(samples_.size() - 1));
    const auto k = std::min(static_cast<std::size_t>(position), samples_.size() - 2);
    const double f = position - static_cast<double>(k);
    const TruthSample& a = samples_[k];
    const TruthSample& b = samples_[k + 1];
    const auto mix = [f](double u, double v) { return u + f * (v - u); };
    TruthSample out;
    out.pose = a.pose + f * (b.pose - a.pose);
    out.ax_mps2 = mix(a.ax_mps2, b.ax_mps2);
    out.ay_mps2 = mix(a.ay_mps2, b.ay_mps2);
    out.yaw_rate_radps = mix(a.yaw_rate_radps, b.yaw_rate_radps);
    out.wheel_angle_rl_rad = mix(a.wheel_angle_rl_rad, b.wheel_angle_rl_rad);
    out.wheel_angle_rr_rad = mix(a.wheel_angle_rr_rad, b.wheel_angle_rr_rad);
    out.wheel_rate_rl_radps = mix(a.wheel_rate_rl_radps, b.wheel_rate_rl_radps);
    out.wheel_rate_rr_radps = mix(a.wheel_rate_rr_radps, b.wheel_rate_rr_radps);
    out.longitudinal_force_n = mix(a.longitudinal_force_n, b.longitudinal_force_n);
    return out;
  }

 private:
  double step_s_;
  std::vector<TruthSample> samples_;
};

}  // namespace

double static_rear_wheel_load_n(const VehicleDynamicsConfig& config, double wheelbase_m) {
  return config.mass_kg * kGravityMps2 * config.cg_to_front_axle_m / wheelbase_m / 2.0;
}

std::array<double, 2> steady_rolling_radii_m(const VehicleDynamicsConfig& config,
                                             double wheelbase_m, double track_width_m,
                                             const StaticRearRadii& radii, double speed_mps) {
  const Vehicle vehicle(config, wheelbase_m, track_width_m, radii);
  return {vehicle.steady_rolling_radius_m(speed_mps, true),
          vehicle.steady_rolling_radius_m(speed_mps, false)};
}

std::unique_ptr<MotionTruth> simulate_vehicle_dynamics(const Path& path,
                                                       const SpeedProfile& profile,
                                                       const VehicleDynamicsConfig& config,
                                                       double wheelbase_m, double track_width_m,
                                                       const StaticRearRadii& radii,
                                                       const std::function<double(double)>& grade) {
  const Vehicle vehicle(config, wheelbase_m, track_width_m, radii);
  const double h = 1.0 / config.step_hz;
  const int steps_per_control =
      std::max(1, static_cast<int>(std::lround(config.step_hz / config.control_hz)));
  const double duration_s = profile.duration_s();
  const auto steps = static_cast<std::size_t>(std::ceil(duration_s / h));
  const double k_lateral = 1.0 / (config.preview_distance_m * config.preview_distance_m);
  const double k_heading = 2.0 / config.preview_distance_m;

  const PathPoint start = path.at(0.0);
  const double b = vehicle.rear_offset_m();
  State s{start.pose.x() + b * std::cos(start.pose.z()),
          start.pose.y() + b * std::sin(start.pose.z()),
          start.pose.z(),
          0.0,
          0.0,
          0.0,
          0.0,
          0.0};
  auto motion = std::make_unique<RecordedMotion>(h);
  double progress_m = 0.0;
  const std::vector<double> cusps_m = path.direction_changes_m();
  Controls controls{0.0, 0.0, Pitch(grade ? grade(0.0) : 0.0)};
  // The force the driver commands; the tyres get it through the actuators' lag, step by step.
  double commanded_force_n = 0.0;
  const double tau = config.actuator_time_constant_s;
  const double follow = tau > 0.0 ? -std::expm1(-h / tau) : 1.0;

  for (std::size_t k = 0; k <= steps; ++k) {
    const double t = static_cast<double>(k) * h;
    const Pose2 rear(s.x - b * std::cos(s.yaw), s.y - b * std::sin(s.yaw), s.yaw);
    if (k % static_cast<std::size_t>(steps_per_control) == 0) {
      const MotionState reference = profile.at(t);
      const int direction = path.at(reference.s_m).direction;
      // Progress: Newton projection of the rear axle onto the path near the last progress,
      // never far ahead of the profile (so a cusp is not crossed before the stop).
      const double previous_m = progress_m;
      const double ahead_limit_m =
          std::min(path.length_m(), reference.s_m + std::max(0.5, 0.1 * std::abs(s.vx)));
      for (int i = 0; i < 3; ++i) {
        const PathPoint p = path.at(progress_m);
        const Eigen::Vector2d tangent =
            p.direction * Eigen::Vector2d(std::cos(p.pose.z()), std::sin(p.pose.z()));
        progress_m += tangent.dot(rear.head<2>() - p.pose.head<2>());
        // Stay local: one control period moves the vehicle centimetres, and a Newton step at a
        // cusp could otherwise land on the other branch.
        const double lowest_m =
            previous_m;  // progress along the path never goes back, even reversing
        progress_m = std::clamp(progress_m, lowest_m,
                                std::max(lowest_m, std::min(ahead_limit_m, previous_m + 2.0)));
      }
      // Standing, a driver holds the brake where the car came to rest, a few centimetres short
      // of the stop: nothing chases the rest, which at the gains' time constant (3 s) would make
      // the car creep through the whole stop (angular-rate wheel sensors read that as a bias).
      // Leaving a cusp from there, progress starts on the new segment.
      const bool standing = reference.speed_mps == 0.0 && reference.acc_mps2 == 0.0;
      for (const double cusp_m : cusps_m) {
        constexpr double kShortOfStopM = 0.3;
        if (progress_m < cusp_m && reference.s_m > cusp_m && cusp_m - progress_m < kShortOfStopM)
          progress_m = std::nextafter(cusp_m, path.length_m());
      }
      const PathPoint p = path.at(progress_m);
      const double lateral = (rear.head<2>() - p.pose.head<2>())
                                 .dot(Eigen::Vector2d(-std::sin(p.pose.z()), std::cos(p.pose.z())));
      const double heading = angle_difference(rear.z(), p.pose.z());
      const double u = -k_lateral * lateral - k_heading * direction * heading;
      controls.steer_rad = std::clamp(std::atan(wheelbase_m * (p.curvature_1pm + u)),
                                      -config.max_steer_rad, config.max_steer_rad);
      const double behind_m = standing ? 0.0 : reference.s_m - progress_m;
      const double acc =
          std::clamp(direction * reference.acc_mps2 +
                         config.speed_gain_1ps * (direction * reference.speed_mps - s.vx) +
                         config.position_gain_1ps2 * direction * behind_m,
                     -config.friction * kGravityMps2, config.friction * kGravityMps2);
      // The driver holds the speed on a hill: the slope's share of the weight is driven (or
      // braked) on top.
      controls.pitch = Pitch(grade ? grade(progress_m) : 0.0);
      commanded_force_n = config.mass_kg * acc + vehicle.resistance_n(s.vx) +
                          config.mass_kg * kGravityMps2 * controls.pitch.sin;
    }
    controls.force_n += follow * (commanded_force_n - controls.force_n);

    double ay = 0.0;
    const Derivative d1 = vehicle.derivative(s, controls, &ay);
    TruthSample sample;
    sample.pose = rear;
    sample.yaw_rate_radps = d1.yaw;
    sample.ax_mps2 = d1.vx - d1.yaw * (vehicle.kinematic(s) ? b * d1.yaw : s.vy);
    sample.ay_mps2 = ay;
    sample.wheel_angle_rl_rad = s.angle_rl;
    sample.wheel_angle_rr_rad = s.angle_rr;
    sample.wheel_rate_rl_radps = d1.angle_rl;
    sample.wheel_rate_rr_radps = d1.angle_rr;
    sample.longitudinal_force_n = controls.force_n;
    motion->add(sample);
    if (k == steps) break;

    const Derivative d2 = vehicle.derivative(step_state(s, d1, h / 2), controls);
    const Derivative d3 = vehicle.derivative(step_state(s, d2, h / 2), controls);
    const Derivative d4 = vehicle.derivative(step_state(s, d3, h), controls);
    const Derivative sum{d1.x + 2 * d2.x + 2 * d3.x + d4.x,
                         d1.y + 2 * d2.y + 2 * d3.y + d4.y,
                         d1.yaw + 2 * d2.yaw + 2 * d3.yaw + d4.yaw,
                         d1.vx + 2 * d2.vx + 2 * d3.vx + d4.vx,
                         d1.vy + 2 * d2.vy + 2 * d3.vy + d4.vy,
                         d1.r + 2 * d2.r + 2 * d3.r + d4.r,
                         d1.angle_rl + 2 * d2.angle_rl + 2 * d3.angle_rl + d4.angle_rl,
                         d1.angle_rr + 2 * d2.angle_rr + 2 * d3.angle_rr + d4.angle_rr};
    s = step_state(s, sum, h / 6.0);
    if (vehicle.kinematic(s)) {  // the kinematic constraint holds the lateral states
      s.r = s.vx * std::tan(controls.steer_rad) / wheelbase_m;
      s.vy = b * s.r;
    }
  }
  return motion;
}

}  // namespace odocal::sim
