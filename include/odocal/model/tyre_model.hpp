#pragma once
// The condition-dependent rolling circumference of a rear wheel (docs/tyre-model.md has the
// derivations): what one revolution carries the wheel over the ground depends on the driving
// state through a few coefficients,
//   c_i,eff = c_i (1 + sum_j k_j x_j,i(state)) / (1 + kappa_i),
// the sum over every term but the physical slip's, kappa_i = -(k_drive_slip x_driving,i +
// k_brake_slip x_braking,i) (tyre_factor_with_gradient), applied as a factor on the wheel's
// revolution increment, so that eqs. 1-2 hold unchanged with c_i, the circumference at rest (what
// the plain model of eqs. 1-2 calls c_i). Two families of regressors x_j,i, for rear wheel i
// (s_RL = +1, s_RR = -1):
// - the regression terms (tyre_model: extended), from the speed v, the lateral acceleration a_y
//   (left positive), the longitudinal acceleration a_x (a_x+ = max(a_x, 0), a_x- = min(a_x, 0))
//   and the yaw rate w:
//     v^2, s_i a_y, -a_x+, -a_x-, w^2, -s_i a_x+ a_y, -s_i a_x- a_y;
// - the physical terms (tyre_model: physical), from the vehicle's body (VehicleBody) and the
//   accelerometer: the wheel's vertical load change and the force over load that its slip
//   follows,
//     -dz_i, -rho_i b(s_d rho_i) (driving), -rho_i b(s_b rho_i) (braking),
//   with dz_i = h a_x / (2 L) - s_i r h a_y / t (per vehicle mass), the tractive acceleration
//   T = a_x + rho_air c_d A v^2 / (2 m) + f_r g + b a_y w / v and rho_i = (T / 2) / (z_0 + dz_i),
//   z_0 the wheel's static load per vehicle mass; b() the slip curve's bend (slip_curve_bend), at
//   the force over load the wheel carries, its axle's share s_d or s_b of the car's; rho_i held
//   where that reaches the wheel's grip (grip_limited).
// With the physical terms, beside the circumference: the rear axle's side slip angle, which
// eqs. 1-2 take as zero, beta = k_side_slip f_y (the rear tyres' slip angle grows with the
// lateral force they carry): the reference point moves at beta from its heading (eq. 1's beta).

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "odocal/model/gravity.hpp"
#include "odocal/options/enum_names.hpp"

namespace odocal {

// Which axle the engine drives. On a front-driven car the rear wheels roll free: no drive slip
// in their speeds, only the brakes' share of slip.
enum class Drivetrain { kRear, kFront, kAll };
template <>
struct EnumNames<Drivetrain> {
  static constexpr std::array<EnumName<Drivetrain>, 3> kTable{
      {{Drivetrain::kRear, "rear"}, {Drivetrain::kFront, "front"}, {Drivetrain::kAll, "all"}}};
};

// What the physical terms need of the vehicle: vehicle.yaml's `body`, with its wheelbase_m and
// track_width_m. The defaults are a mid-size passenger car.
struct VehicleBody {
  double wheelbase_m = 2.7;             // L
  double track_width_m = 1.6;           // t: the rear track (vehicle.yaml's track_width_m)
  double rear_axle_load_share = 0.463;  // of the weight at rest (b = (1 - share) L from the CG)
  double cg_height_m = 0.55;            // h
  double rear_roll_share = 0.45;        // r: the rear axle's share of the lateral load transfer
  double mass_kg = 1500.0;              // m
  double drag_area_m2 = 0.7;            // c_d A
  double rolling_resistance = 0.012;    // f_r
  // The slip curve (slip_curve_bend): the tyres' grip on the road, the magic formula's shape
  // factor C of the longitudinal force, and the rear axle's share of the brakes' force and, on an
  // all-wheel-driven car, of the drive's.
  double friction = 1.0;
  double slip_curve_shape = 1.65;
  double brake_rear_share = 0.35;
  double all_wheel_drive_rear_share = 0.6;
  // The front and rear tyres' cornering stiffness per unit load (1/rad) and the magic formula's
  // shape factor of their lateral force: how far the front wheels are steered beyond L w / v
  // (their slip angle less the rear's), which turns their lateral force against the car's motion
  // (cornering_drag). A car that understeers has the stiffer rear.
  double front_cornering_stiffness = 16.0;
  double rear_cornering_stiffness = 19.0;
  double lateral_curve_shape = 1.3;
  // Which axle the drive's share above goes to, and what a coefficient held at zero is taken to
  // be uncertain by (tyre_car_prior.hpp). Unstated: a driven rear axle's, which covers every car.
  std::optional<Drivetrain> drivetrain;
  // Where the accelerometer sits, forward and left of the rear axle's centre (vehicle.yaml's
  // imu_x_m, imu_y_m, set by VehicleConfig::body_geometry()); unstated: at the centre of gravity.
  std::optional<Eigen::Vector2d> imu_position_m;
};

// What air drag and rolling resistance take per kilogram from a car moving forward at speed_mps
// on the level: the force the tyres give to hold its speed. One formula for the tyre model and for
// the check of a log's drive force (the simulator keeps its own, as the truth it is).
struct RoadResistance {
  double drag_mps2{}, rolling_mps2{};
  double total() const { return drag_mps2 + rolling_mps2; }
};
inline RoadResistance road_resistance(const VehicleBody& body, double speed_mps) {
  constexpr double kAirDensity = 1.2;
  return {0.5 * kAirDensity * body.drag_area_m2 / body.mass_kg * speed_mps * speed_mps,
          body.rolling_resistance * kGravityMps2};
}

enum class TyreTerms { kRegression, kPhysical };

// The batch's tyre_model option that fits a family of terms.
inline const char* tyre_model_option(TyreTerms terms) {
  return terms == TyreTerms::kPhysical ? "physical" : "extended";
}

// Coefficients, all zero for the plain model.
struct TyreModel {
  double k_speed_s2pm2 = 0.0;   // per (m/s)^2: tyre growth and the drag's slip on a driven axle
  double k_lateral_s2pm = 0.0;  // per m/s^2: lateral load transfer (outer wheel rolls smaller)
  double k_drive_s2pm = 0.0;    // per m/s^2 of acceleration: drive slip, rearward load transfer
  double k_brake_s2pm = 0.0;    // per m/s^2 of deceleration: brake slip, forward load transfer
  double k_turn_s2prad2 = 0.0;  // per (rad/s)^2 of yaw rate: a driven axle's cornering drag
  // Per (m/s^2)^2: the slip of the inner wheel, unloaded in a turn, against the outer one's
  // (slip is force over load, and a turn moves load to the outer wheel).
  double k_drive_lateral_s4pm2 = 0.0;
  double k_brake_lateral_s4pm2 = 0.0;
  // Physical: the radius's load sensitivity (radius per newton times mass over radius), per
  // m/s^2 of load change per vehicle mass; and the slip per unit of force over load, driving and
  // braking (the rear axle's share of the force over the tyre's slip stiffness).
  double k_load_s2pm = 0.0;
  double k_drive_slip = 0.0;
  double k_brake_slip = 0.0;
  // The rear axle's side slip angle per m/s^2 of lateral specific force (rad per m/s^2):
  // negative, the axle slides outwards (about -1 / (g C_alpha/F_z), -5e-3 for C_alpha/F_z = 19).
  double k_side_slip_s2pm = 0.0;

  static constexpr int kCoefficients = 11;
  using Vector = Eigen::Matrix<double, kCoefficients, 1>;
  Vector coefficients() const;
  static TyreModel from(const Vector& k);
  bool plain() const { return coefficients().isZero(0.0); }
};

// Every coefficient: its key (vehicle.yaml's tyre_model, Python's tyre_model dict; a
// calibration's parameter is "tyre_" and the key without its "k_"), its bounds (far beyond any
// tyre, so that a typo cannot turn a circumference negative when driving) and its family; in the
// order of TyreModel::Vector.
struct TyreCoefficient {
  const char* key;
  double TyreModel::*member;
  double min, max;
  TyreTerms terms;
};
inline constexpr std::array<TyreCoefficient, TyreModel::kCoefficients> kTyreCoefficients{{
    {"k_speed_s2pm2", &TyreModel::k_speed_s2pm2, -1e-4, 1e-4, TyreTerms::kRegression},
    {"k_lateral_s2pm", &TyreModel::k_lateral_s2pm, -0.01, 0.01, TyreTerms::kRegression},
    {"k_drive_s2pm", &TyreModel::k_drive_s2pm, -0.1, 0.1, TyreTerms::kRegression},
    {"k_brake_s2pm", &TyreModel::k_brake_s2pm, -0.1, 0.1, TyreTerms::kRegression},
    {"k_turn_s2prad2", &TyreModel::k_turn_s2prad2, -1.0, 1.0, TyreTerms::kRegression},
    {"k_drive_lateral_s4pm2", &TyreModel::k_drive_lateral_s4pm2, -0.1, 0.1, TyreTerms::kRegression},
    {"k_brake_lateral_s4pm2", &TyreModel::k_brake_lateral_s4pm2, -0.1, 0.1, TyreTerms::kRegression},
    {"k_load_s2pm", &TyreModel::k_load_s2pm, -0.05, 0.05, TyreTerms::kPhysical},
    {"k_drive_slip", &TyreModel::k_drive_slip, -1.0, 1.0, TyreTerms::kPhysical},
    {"k_brake_slip", &TyreModel::k_brake_slip, -1.0, 1.0, TyreTerms::kPhysical},
    {"k_side_slip_s2pm", &TyreModel::k_side_slip_s2pm, -0.05, 0.05, TyreTerms::kPhysical},
}};
// Its index in TyreModel::Vector: the one coefficient that turns the course, not the wheels.
inline constexpr int kSideSlipCoefficient = 10;
// The drive slip's index: the one that a stated front drivetrain fixes (the rear wheels roll free).
inline constexpr int kDriveSlipCoefficient = 8;
inline constexpr int kBrakeSlipCoefficient = 9;
// The steady straight speed at which a tyre model's circumference is reported by default
// (gentle driving's): the batch's reference_speed_mps and the simulator's truth of it.
inline constexpr double kDefaultReferenceSpeedMps = 5.0;
inline std::string tyre_parameter_name(const TyreCoefficient& coefficient) {
  return std::string("tyre_") + (coefficient.key + 2);
}

inline TyreModel::Vector TyreModel::coefficients() const {
  Vector k;
  for (std::size_t j = 0; j < kTyreCoefficients.size(); ++j)
    k(static_cast<int>(j)) = this->*(kTyreCoefficients[j].member);
  return k;
}
inline TyreModel TyreModel::from(const Vector& k) {
  TyreModel model;
  for (std::size_t j = 0; j < kTyreCoefficients.size(); ++j)
    model.*(kTyreCoefficients[j].member) = k(static_cast<int>(j));
  return model;
}

// The driving state at one wheel sample (tyre_model's regressors come from it), in single
// precision: a long drive keeps one per wheel sample, and a state measured over half a second is
// not known to seven digits.
struct DrivingState {
  float speed_mps{};
  float longitudinal_mps2{};  // a_x from the wheels' speed, forward positive
  float yaw_rate_radps{};     // w, counter-clockwise positive
  // The accelerometer's specific force, forward and left (what the tyres push the body with; on
  // a slope it includes gravity's share, as the drive force does); without an accelerometer the
  // wheels' a_x and v w.
  float specific_force_x_mps2{};
  float specific_force_y_mps2{};
  // The tyres' total longitudinal force over this sample's increment where the log gives it
  // (WheelStream::drive_force_n), N; NaN: not given, the accelerometer says it.
  float drive_force_n = std::numeric_limits<float>::quiet_NaN();
  // dw/dt: the yaw rate's change over the state's window (a car that fishtails turns the front
  // tyres' force against its yaw inertia, and steers them beyond L w / v).
  float yaw_acceleration_radps2{};

  // a_y = v w, left positive: computed, not stored (28 bytes per wheel sample, not 32).
  double lateral_mps2() const { return static_cast<double>(speed_mps) * yaw_rate_radps; }
  bool force_given() const { return std::isfinite(drive_force_n); }
};

// The centre of gravity's distance ahead of the rear axle, from the axles' loads at rest.
inline double cg_ahead_of_rear_axle_m(const VehicleBody& body) {
  return (1.0 - body.rear_axle_load_share) * body.wheelbase_m;
}

// Where the accelerometer sits, from the rear axle's centre (forward, left): vehicle.yaml's
// imu_x_m and imu_y_m, else at the centre of gravity, where an unstated IMU's readings are taken.
inline Eigen::Vector2d accelerometer_position_m(const VehicleBody& body) {
  return body.imu_position_m.value_or(Eigen::Vector2d(cg_ahead_of_rear_axle_m(body), 0.0));
}

// The accelerometer's specific force at the centre of gravity, forward and left, which the
// physical terms' load transfer and force are of: an IMU r ahead of it (and left) reads its turn's
// -w^2 r and dw/dt r beside the body's. The state's w is its mean over +-0.25 s and dw/dt the
// gyro's over +-0.05 s, so the gyro's noise barely adds.
inline Eigen::Vector2d specific_force_at_cg(const DrivingState& state, const VehicleBody& body) {
  const Eigen::Vector2d read(state.specific_force_x_mps2, state.specific_force_y_mps2);
  if (!body.imu_position_m) return read;  // taken as at the centre of gravity
  const Eigen::Vector2d r =
      *body.imu_position_m - Eigen::Vector2d(cg_ahead_of_rear_axle_m(body), 0.0);
  const double w = state.yaw_rate_radps, w_dot = state.yaw_acceleration_radps2;
  return read + Eigen::Vector2d(w * w * r.x() + w_dot * r.y(), -w_dot * r.x() + w * w * r.y());
}

enum class RearWheel { kLeft, kRight };

// The rear axle's share of the drive force.
inline double drive_rear_share(const VehicleBody& body) {
  switch (body.drivetrain.value_or(Drivetrain::kRear)) {
    case Drivetrain::kFront:
      return 0.0;
    case Drivetrain::kAll:
      return body.all_wheel_drive_rear_share;
    case Drivetrain::kRear:
      break;
  }
  return 1.0;
}

// The magic formula sin(C atan(u)) = x inverted for u, times C: C tan(asin(x) / C), which is
// x (1 + (1 / 6 + 1 / (3 C^2)) x^2 + ...). Both the slip curve and the lateral curve use it.
inline double magic_formula_inverse(double x, double shape) {
  return shape * std::tan(std::asin(x) / shape);
}

// The slip curve's bend: the slip that transmits a force F on a load F_z, over its linear part
// F / (C_k F_z). The magic formula F = mu F_z sin(C atan(B k)) with B = C_k / (C mu), inverted,
// gives k = tan(asin(x) / C) / B at x = F / (mu F_z), so the bend is C tan(asin(x) / C) / x:
// 1 + (1 / 6 + 1 / (3 C^2)) x^2 + ..., 1.24 at x = 0.75 for C = 1.65. A wheel at its grip limit
// spins or locks, where the slip follows no force: x is held below 0.99.
inline double slip_curve_bend(double force_over_load, const VehicleBody& body) {
  const double x = std::min(std::abs(force_over_load) / body.friction, 0.99);
  if (x < 1e-6) return 1.0;
  return magic_formula_inverse(x, body.slip_curve_shape) / x;
}

// The force over load that a wheel carrying axle_share of its axle's pair can transmit: at most
// its grip (0.99 mu, where slip_curve_bend holds). Past it the wheel spins or locks at the slip
// curve's end, so its slip regressor stays there instead of growing with the demand.
inline double grip_limited(double force_over_load, double axle_share, const VehicleBody& body) {
  if (axle_share <= 0.0) return force_over_load;
  const double limit = 0.99 * body.friction / axle_share;
  return std::clamp(force_over_load, -limit, limit);
}

// The slip angle (rad) at which a tyre of this cornering stiffness per unit load carries the
// lateral force over load y: the lateral magic formula inverted (B = C_a / (C mu)), its force held
// below the grip as slip_curve_bend holds the longitudinal one.
inline double slip_angle_rad(double force_over_load, double stiffness, const VehicleBody& body) {
  const double mu = body.friction;
  const double x = std::clamp(force_over_load / mu, -0.99, 0.99);
  return magic_formula_inverse(x, body.lateral_curve_shape) * mu / stiffness;
}

// What the front tyres' lateral force takes from the car's forward motion, per unit mass
// (m/s^2): their force F_yf along wheels steered by delta, F_yf delta. The two axles' lateral
// forces hold the lateral specific force f_y and turn the yaw inertia (taken as m a b, a car's
// dynamic index of one): F_yf / m = b (f_y + a dw/dt) / L, F_yr / m = a (f_y - b dw/dt) / L. The
// front wheels point along the car's path at the front axle plus their slip angle, so
// delta = L w / v + alpha_f - alpha_r: a car that understeers steers more than L w / v, and one
// that fishtails (dw/dt) steers against its turn. The axles' loads move with the body's
// acceleration f_x (not the wheels': a spinning wheel's is not the body's). On Hockenheim's fast
// kink the force the accelerometer then leaves to the rear tyres is within 0.02 m/s^2 of the
// simulator's, from 0.12 with F_yf = m b f_y / L along L w / v (docs/tyre-model.md, "The front
// tyres' steer").
inline double cornering_drag_at_mps2(const DrivingState& state, const VehicleBody& body, double f_x,
                                     double f_y) {
  const double L = body.wheelbase_m, a = body.rear_axle_load_share * L, b = L - a;
  const double w = state.yaw_rate_radps, w_dot = state.yaw_acceleration_radps2;
  const double v = std::max(static_cast<double>(state.speed_mps), 1.0);
  const double front = b * (f_y + a * w_dot) / L, rear = a * (f_y - b * w_dot) / L;
  const double shift = body.cg_height_m * f_x / L;
  const double front_load = std::max(kGravityMps2 * b / L - shift, 0.1 * kGravityMps2 * b / L);
  const double rear_load = std::max(kGravityMps2 * a / L + shift, 0.1 * kGravityMps2 * a / L);
  const double steer = L * w / v +
                       slip_angle_rad(front / front_load, body.front_cornering_stiffness, body) -
                       slip_angle_rad(rear / rear_load, body.rear_cornering_stiffness, body);
  return front * steer;
}

// The same at the state's own forward force: the accelerometer's, or where the log gives the
// tyres' force, the body's acceleration that force leaves (the force less the resistances and
// this drag, a fixed point that contracts by the drag's few percent per m/s^2 of load shift), so
// that a given force is never mixed with the accelerometer's forward reading.
inline double cornering_drag_mps2(const DrivingState& state, const VehicleBody& body,
                                  const Eigen::Vector2d& at_cg) {
  if (!state.force_given()) return cornering_drag_at_mps2(state, body, at_cg.x(), at_cg.y());
  const double pushed =
      state.drive_force_n / body.mass_kg - road_resistance(body, state.speed_mps).total();
  double drag = 0.0;
  for (int pass = 0; pass < 8; ++pass) {
    const double next = cornering_drag_at_mps2(state, body, pushed - drag, at_cg.y());
    if (std::abs(next - drag) < 1e-9) return next;
    drag = next;
  }
  return drag;
}
inline double cornering_drag_mps2(const DrivingState& state, const VehicleBody& body) {
  return cornering_drag_mps2(state, body, specific_force_at_cg(state, body));
}

// What both rear wheels' regressors share at one state, per vehicle mass: the forward force the
// tyres transmit, the body's forward acceleration that it leaves (which moves the loads), and its
// lateral specific force at the centre of gravity.
struct AxleForces {
  double tractive_mps2, forward_mps2, lateral_mps2;
};
inline AxleForces axle_forces(const DrivingState& state, const VehicleBody& body) {
  const RoadResistance road = road_resistance(body, state.speed_mps);
  const double drag = road.drag_mps2, rolling = road.rolling_mps2;
  const Eigen::Vector2d at_cg = specific_force_at_cg(state, body);
  const double cornering = cornering_drag_mps2(state, body, at_cg);
  // A force the log gives is the tyres' own, without the accelerometer's noise; what is left of
  // it beyond the resistances accelerates the body and moves its load.
  if (state.force_given()) {
    const double tractive = state.drive_force_n / body.mass_kg;
    return {tractive, tractive - drag - rolling - cornering, at_cg.y()};
  }
  return {at_cg.x() + drag + rolling + cornering, at_cg.x(), at_cg.y()};
}

// d(c_i,eff / c_i) / d coefficients at this state, for one wheel (zero for the side slip), given
// the state's axle_forces.
inline TyreModel::Vector tyre_regressors(const DrivingState& state, RearWheel wheel,
                                         const VehicleBody& body, const AxleForces& forces) {
  const double side = wheel == RearWheel::kLeft ? 1.0 : -1.0;
  const double v = state.speed_mps, w = state.yaw_rate_radps;
  const double a_x = state.longitudinal_mps2;
  const double drive = a_x > 0.0 ? -a_x : 0.0, brake = a_x < 0.0 ? -a_x : 0.0;
  const double turn = side * state.lateral_mps2();
  // Physical: per vehicle mass, the wheel's load and the force its axle transmits. The lateral
  // force is the accelerometer's, not v w: where the car slides (a fishtail) the two part, and
  // the tyres carry what the accelerometer reads.
  const double L = body.wheelbase_m, h = body.cg_height_m;
  const double tractive = forces.tractive_mps2, f_x = forces.forward_mps2;
  const double f_y = forces.lateral_mps2;
  const double static_load = 0.5 * kGravityMps2 * body.rear_axle_load_share;
  const double load_change =
      h * f_x / (2.0 * L) - side * body.rear_roll_share * h * f_y / body.track_width_m;
  // A wheel that the turn lifts keeps a tenth of its load: beyond, nothing is linear anyway.
  const double force_over_load =
      0.5 * tractive / std::max(static_load + load_change, 0.1 * static_load);
  // The wheel carries its axle's share of the car's force over load: k_drive_slip and
  // k_brake_slip hold that share over the slip stiffness, the bend its force.
  const double drive_share = drive_rear_share(body), brake_share = body.brake_rear_share;
  const double driven = grip_limited(force_over_load, drive_share, body);
  const double braked = grip_limited(force_over_load, brake_share, body);
  const double driving =
      tractive > 0.0 ? -driven * slip_curve_bend(drive_share * driven, body) : 0.0;
  const double braking =
      tractive < 0.0 ? -braked * slip_curve_bend(brake_share * braked, body) : 0.0;
  return (TyreModel::Vector() << v * v, turn, drive, brake, w * w, drive * turn, brake * turn,
          -load_change, driving, braking, 0.0)
      .finished();
}

inline TyreModel::Vector tyre_regressors(const DrivingState& state, RearWheel wheel,
                                         const VehicleBody& body) {
  return tyre_regressors(state, wheel, body, axle_forces(state, body));
}

// d beta / d k_side_slip: the lateral specific force.
inline double side_slip_regressor(const DrivingState& state, const VehicleBody& body) {
  return specific_force_at_cg(state, body).y();
}

// The rear axle's side slip angle at this state, rad (left of the heading positive).
inline double side_slip_rad(const TyreModel& model, const DrivingState& state,
                            const VehicleBody& body) {
  return model.k_side_slip_s2pm * side_slip_regressor(state, body);
}

// c_i,eff / c_i, and its gradient in the coefficients (the batch linearises about them).
struct TyreFactor {
  double value;
  TyreModel::Vector gradient;
};
inline TyreFactor tyre_factor_at_regressors(const TyreModel& model, const TyreModel::Vector& x) {
  const TyreModel::Vector k = model.coefficients();
  TyreModel::Vector slip = TyreModel::Vector::Zero();
  slip(kDriveSlipCoefficient) = x(kDriveSlipCoefficient);
  slip(kBrakeSlipCoefficient) = x(kBrakeSlipCoefficient);
  const TyreModel::Vector rest = x - slip;
  // The physical terms' slip divides: a wheel at slip kappa turns 1 + kappa times for its ground
  // (SAE slip, which the magic formula takes), so its circumference is c / (1 + kappa), not
  // c (1 - kappa). The kappa^2 that the linear form leaves out is 5e-4 (1 mm of circumference)
  // in a 2 m/s^2 drive of a rear-driven car. Past half a wheel's speed it spins or locks, where no
  // curve holds (and a solver's trial coefficients cannot divide by zero).
  constexpr double kLargestSlip = 0.5;
  const double kappa = -k.dot(slip);
  const double held = std::clamp(kappa, -kLargestSlip, kLargestSlip);
  const double numerator = 1.0 + k.dot(rest);
  TyreModel::Vector gradient = rest / (1.0 + held);
  if (held == kappa) gradient += numerator / ((1.0 + held) * (1.0 + held)) * slip;
  return {numerator / (1.0 + held), gradient};
}

inline TyreFactor tyre_factor_with_gradient(const TyreModel& model, const DrivingState& state,
                                            RearWheel wheel, const VehicleBody& body) {
  return tyre_factor_at_regressors(model, tyre_regressors(state, wheel, body));
}

// Both rear wheels' factors at one state, its axle forces (and their cornering drag) computed once.
struct RearTyreFactors {
  TyreFactor left, right;
};
inline RearTyreFactors rear_tyre_factors_with_gradient(const TyreModel& model,
                                                       const DrivingState& state,
                                                       const VehicleBody& body) {
  const AxleForces forces = axle_forces(state, body);
  return {
      tyre_factor_at_regressors(model, tyre_regressors(state, RearWheel::kLeft, body, forces)),
      tyre_factor_at_regressors(model, tyre_regressors(state, RearWheel::kRight, body, forces))};
}

inline double tyre_factor(const TyreModel& model, const DrivingState& state, RearWheel wheel,
                          const VehicleBody& body) {
  return tyre_factor_with_gradient(model, state, wheel, body).value;
}

}  // namespace odocal
