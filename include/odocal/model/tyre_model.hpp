#pragma once
// The condition-dependent rolling circumference of a rear wheel (docs/tyre-model.md has the
// derivation): what one revolution carries the wheel over the ground depends on the driving
// state through a few coefficients,
//   c_i,eff = c_i (1 + k_speed v^2 + s_i k_lateral a_y - k_drive a_x+ - k_brake a_x-
//                  + k_turn w^2 - s_i k_drive_lateral a_x+ a_y - s_i k_brake_lateral a_x- a_y),
// a_x+ = max(a_x, 0), a_x- = min(a_x, 0), s_RL = +1, s_RR = -1. v is the speed, a_y the lateral
// acceleration (left positive, v times the yaw rate w), a_x the longitudinal acceleration. c_i is
// the circumference at rest and at zero acceleration (what the plain model of eqs. 1-2 calls
// c_i). Applied as a factor on the wheel's revolution increment, so that eqs. 1-2 hold unchanged
// with c_i.

#include <Eigen/Core>
#include <array>
#include <string>

namespace odocal {

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

  static constexpr int kCoefficients = 7;
  using Vector = Eigen::Matrix<double, kCoefficients, 1>;
  Vector coefficients() const {
    return (Vector() << k_speed_s2pm2, k_lateral_s2pm, k_drive_s2pm, k_brake_s2pm, k_turn_s2prad2,
            k_drive_lateral_s4pm2, k_brake_lateral_s4pm2)
        .finished();
  }
  static TyreModel from(const Vector& k) { return {k(0), k(1), k(2), k(3), k(4), k(5), k(6)}; }
  bool plain() const { return coefficients().isZero(0.0); }
};

// Every coefficient's key (vehicle.yaml's tyre_model, Python's tyre_model dict; a calibration's
// parameter is "tyre_" and the key without its "k_"), in the order of TyreModel::Vector.
struct TyreCoefficientName {
  const char* key;
  double TyreModel::*member;
};
inline constexpr std::array<TyreCoefficientName, TyreModel::kCoefficients> kTyreCoefficientNames{
    {{"k_speed_s2pm2", &TyreModel::k_speed_s2pm2},
     {"k_lateral_s2pm", &TyreModel::k_lateral_s2pm},
     {"k_drive_s2pm", &TyreModel::k_drive_s2pm},
     {"k_brake_s2pm", &TyreModel::k_brake_s2pm},
     {"k_turn_s2prad2", &TyreModel::k_turn_s2prad2},
     {"k_drive_lateral_s4pm2", &TyreModel::k_drive_lateral_s4pm2},
     {"k_brake_lateral_s4pm2", &TyreModel::k_brake_lateral_s4pm2}}};
inline std::string tyre_parameter_name(const TyreCoefficientName& name) {
  return std::string("tyre_") + (name.key + 2);
}

// The driving state at one wheel sample (tyre_model's regressors come from it).
struct DrivingState {
  double speed_mps{};
  double lateral_mps2{};       // a_y, left positive
  double longitudinal_mps2{};  // a_x, forward positive
  double yaw_rate_radps{};     // w, counter-clockwise positive
};

enum class RearWheel { kLeft, kRight };

// d(c_i,eff / c_i) / d coefficients at this state, for one wheel.
inline TyreModel::Vector tyre_regressors(const DrivingState& state, RearWheel wheel) {
  const double side = wheel == RearWheel::kLeft ? 1.0 : -1.0;
  const double a_x = state.longitudinal_mps2;
  const double drive = a_x > 0.0 ? -a_x : 0.0, brake = a_x < 0.0 ? -a_x : 0.0;
  const double turn = side * state.lateral_mps2;
  return (TyreModel::Vector() << state.speed_mps * state.speed_mps, turn, drive, brake,
          state.yaw_rate_radps * state.yaw_rate_radps, drive * turn, brake * turn)
      .finished();
}

// c_i,eff / c_i.
inline double tyre_factor(const TyreModel& model, const DrivingState& state, RearWheel wheel) {
  return 1.0 + model.coefficients().dot(tyre_regressors(state, wheel));
}

}  // namespace odocal
