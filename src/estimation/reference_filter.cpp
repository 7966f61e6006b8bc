#include "odocal/estimation/reference_filter.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>

#include "covariance_update.hpp"
#include "doppler_scale.hpp"
#include "hot_loop.hpp"
#include "odocal/error.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/gravity.hpp"
#include "odocal/model/reference_motion.hpp"
#include "odocal/model/tyre_car_prior.hpp"
#include "sensor_event_merge.hpp"

namespace odocal {
namespace {

// [x, y, vx, vy, yaw, accelerometer bias x, y, gyro bias] (odocal/model/reference_motion.hpp):
// the biases absorb a mounted (e.g. tilted phone) IMU's misalignment and drift; GNSS and Doppler
// make them observable.
constexpr int kStates = kReferenceStates;
using State = ReferenceState;
using Covariance = ReferenceJacobian;
using Coupling = Eigen::Matrix<double, 5, 6>;  // the transition's off-identity block
// How far from the rear axle a car's GNSS antenna may sit, forward: a roof's length; and how far
// from its stated place (vehicle.yaml's gnss_x_m) a measured one may be.
constexpr double kAntennaPlaceSigmaM = 1.5;
constexpr double kStatedAntennaPlaceSigmaM = 0.1;
// The antenna's place, where vehicle.yaml states one off the axle.
std::optional<Eigen::Vector2d> stated_antenna(const VehicleConfig& vehicle) {
  if (!vehicle.gnss_position_m || vehicle.gnss_position_m->isZero()) return std::nullopt;
  return vehicle.gnss_position_m;
}
// The lateral-velocity update waits until the velocity is known to this share of the speed.
constexpr double kLinearVelocityShare = 0.1;

class ReferenceEkf {
 public:
  ReferenceEkf(const Log& log, const ReferenceOptions& options) : log_(log), options_(options) {}

  // At the first fix: the axle is where the antenna's place at this yaw puts it.
  void initialise(double t_s, const Eigen::Vector2d& fix, double yaw_rad, double yaw_sigma) {
    t_s_ = t_s;
    x_ << fix, 0.0, 0.0, yaw_rad, 0.0, 0.0, 0.0;
    if (antenna_m_) x_.head<2>() -= reference_antenna_position(x_, *antenna_m_) - fix;
    P_ = Covariance::Zero();
    // Without an IMU the biases have no input to act on: zero variance freezes them at zero.
    const double acc_bias = log_.imu ? square(options_.acc_bias_sigma_mps2) : 0.0;
    const double gyro_bias = log_.imu ? square(options_.gyro_bias_sigma_radps) : 0.0;
    P_.diagonal() << square(gnss_sigma(0)), square(gnss_sigma(0)), 100.0, 100.0, square(yaw_sigma),
        acc_bias, acc_bias, gyro_bias;
  }

  // Propagates to t_s; returns the transition Jacobian (for the smoother).
  ODOCAL_HOT_LOOP Covariance predict(double t_s) {
    const double dt = t_s - t_s_;
    if (dt <= 0.0) return Covariance::Identity();
    Covariance F;
    x_ = predict_reference(x_, imu_at(0.5 * (t_s_ + t_s)), dt, &F);
    // F = I + E with E on rows 0-4 and columns 2-7 only.
    Coupling E = F.block<5, 6>(0, 2);
    E(2, 0) -= 1.0;
    E(3, 1) -= 1.0;
    E(4, 2) -= 1.0;
    propagate_coupled_block(P_, E);

    // Variance of the acceleration (yaw rate) held over this step: the IMU sample's own noise, or
    // without an IMU the spectral density over dt; plus the random walk for unmodelled effects.
    const double acc_var =
        (log_.imu ? square(options_.acc_sigma_mps2) : options_.no_imu_acc_psd / dt) +
        square(options_.acc_random_walk_mps2) * dt;
    const double yaw_rate_var =
        (log_.imu ? square(options_.yaw_rate_sigma_radps) : options_.no_imu_yaw_rate_psd / dt) +
        square(options_.yaw_random_walk_radps) * dt;
    // The process noise enters position, velocity and yaw (rows 0-4).
    Eigen::Matrix<double, 5, 3> G = Eigen::Matrix<double, 5, 3>::Zero();
    G.block<2, 2>(0, 0) = 0.5 * dt * dt * Eigen::Matrix2d::Identity();
    G.block<2, 2>(2, 0) = dt * Eigen::Matrix2d::Identity();
    G(4, 2) = dt;
    const Eigen::Vector3d noise(acc_var, acc_var, yaw_rate_var);
    P_.topLeftCorner<5, 5>() += (G * noise.asDiagonal()).lazyProduct(G.transpose());
    if (log_.imu) {  // slow bias drift
      P_(5, 5) += square(options_.acc_bias_random_walk_mps2) * dt;
      P_(6, 6) += square(options_.acc_bias_random_walk_mps2) * dt;
      P_(7, 7) += square(options_.gyro_bias_random_walk_radps) * dt;
    }
    P_ = 0.5 * (P_ + P_.transpose());
    t_s_ = t_s;
    return F;
  }

  // Sample k is in effect until sample k + 1, and the readings run linear between the two: held
  // instead, the gyro's turn would lag by half a sample (the batch's gyro is its trapezoid too).
  // The yaw rate's slope moves an IMU that sits off the reference point (vehicle.yaml's imu_x_m,
  // imu_y_m; the fixes are taken as the rear axle's, as everywhere in layer 1); its steps add up
  // to the rate's total change, so the gyro's noise in them does not accumulate in the velocity.
  void set_imu(std::size_t k) {
    const ImuStream& imu = *log_.imu;
    imu_ = {imu.ax_mps2[k], imu.ay_mps2[k], imu.wz_radps[k], 0.0,
            log_.vehicle.imu_position_m.value_or(Eigen::Vector2d::Zero())};
    imu_t_s_ = imu.t_s[k];
    imu_span_s_ = 0.0;
    if (k + 1 < imu.size() && imu.t_s[k + 1] > imu.t_s[k]) {
      imu_span_s_ = imu.t_s[k + 1] - imu.t_s[k];
      imu_slope_ = {(imu.ax_mps2[k + 1] - imu.ax_mps2[k]) / imu_span_s_,
                    (imu.ay_mps2[k + 1] - imu.ay_mps2[k]) / imu_span_s_,
                    (imu.wz_radps[k + 1] - imu.wz_radps[k]) / imu_span_s_};
    }
  }

  // The IMU's reading at t_s (a step's middle): the midpoint rule is then exact for the velocity.
  ImuSample imu_at(double t_s) const {
    if (imu_span_s_ <= 0.0) return imu_;
    const double elapsed = std::clamp(t_s - imu_t_s_, 0.0, imu_span_s_);
    ImuSample reading = imu_;
    reading.ax_mps2 += elapsed * imu_slope_.ax_mps2;
    reading.ay_mps2 += elapsed * imu_slope_.ay_mps2;
    reading.wz_radps += elapsed * imu_slope_.wz_radps;
    reading.wz_dot_radps2 = imu_slope_.wz_radps;
    return reading;
  }

  // The GNSS and heading models select states (reference_position, reference_yaw: H = [0 I 0]),
  // so their updates take P's rows and columns directly (joseph_update_selected). A stated antenna
  // off the axle (vehicle.yaml's gnss_x_m, gnss_y_m) adds the yaw's column.
  ODOCAL_HOT_LOOP bool update_gnss(std::size_t k) {
    const Eigen::Vector2d fix(log_.gnss.x_m[k], log_.gnss.y_m[k]);
    const Eigen::Matrix2d R = square(gnss_sigma(k)) * Eigen::Matrix2d::Identity();
    if (antenna_m_) return update_antenna_position(fix, R);
    const Eigen::Vector2d innovation = fix - reference_position(x_);
    // H P H^T and P H^T are P's top-left block and first two columns (H = [I 0]).
    const Eigen::Matrix2d S = P_.topLeftCorner<2, 2>() + R;
    // S >= R = sigma^2 I is well conditioned: the closed-form inverse is as accurate as a
    // Cholesky solve, without the latter's dynamic-size kernels for the 2x8 right-hand side.
    const Eigen::Matrix2d S_inverse = S.inverse();
    if (!within_gate(innovation, S_inverse)) return false;
    const Eigen::Matrix<double, kStates, 2> K = P_.leftCols<2>().lazyProduct(S_inverse);
    x_ += K * innovation;
    P_ = joseph_update_selected(P_, K, kReferencePositionIndex, R);
    return true;
  }

  // Doppler speed over ground, of the antenna: the turn is the gyro's at the fix.
  ODOCAL_HOT_LOOP void update_speed(double measured_mps) {
    if (x_.segment<2>(2).norm() < options_.gnss_speed_min_mps ||
        measured_mps < options_.gnss_speed_min_mps) {
      return;
    }
    ReferenceRowJacobian H;
    const double predicted =
        antenna_m_
            ? reference_antenna_speed(x_, *antenna_m_, log_.imu ? imu_at(t_s_).wz_radps : 0.0, &H)
            : reference_speed(x_, &H);
    const double innovation = measured_mps - predicted;
    const double R = square(options_.gnss_speed_sigma_mps);
    const double S = H.lazyProduct(P_).dot(H) + R;
    const Eigen::Matrix<double, kStates, 1> K = P_.lazyProduct(H.transpose()) / S;
    x_ += K * innovation;
    P_ = joseph_update_thin(P_, K, H, Eigen::Matrix<double, 1, 1>(R));
  }

  ODOCAL_HOT_LOOP void update_yaw(double measured_rad, double sigma_rad) {
    const double innovation = angle_difference(measured_rad, reference_yaw(x_));
    const double R = square(sigma_rad);
    const double S = P_(kReferenceYawIndex, kReferenceYawIndex) + R;
    const Eigen::Matrix<double, kStates, 1> K = P_.col(kReferenceYawIndex) / S;
    x_ += K * innovation;
    P_ = joseph_update_selected(P_, K, kReferenceYawIndex, Eigen::Matrix<double, 1, 1>(R));
  }

  // The velocity's course as a heading pseudo-measurement (no heading.csv): vehicles move where
  // they point, up to side slip.
  void update_course() {
    if (x_.segment<2>(2).norm() < options_.course_min_speed_mps) return;
    update_yaw(std::atan2(x_(3), x_(2)), options_.course_sigma_rad);
  }

  // The non-holonomic constraint: the rear axle moves along its heading up to its side slip.
  // Held where the car drives nearly straight (the gyro's turn, less its bias, and the lateral
  // acceleration v w below the options' limits), where the slip is small whatever the tyres:
  // taken as zero, its size at a car's (tyre_car_prior.hpp) k a_y v is left in the noise. An
  // expected slip of k a_y v instead put the fast kinks of the ideal circuit (no slip at all) into
  // the reference and +0.24 mm into the iterative method's circumferences. The fixes are the
  // antenna's, which layer 1 takes as the axle's: one x ahead of it moves w x sideways, also
  // left in the noise. Without an IMU there is no turn to go by.
  ODOCAL_HOT_LOOP bool update_lateral_velocity() {
    const double speed = x_.segment<2>(2).norm();
    if (options_.lateral_velocity_sigma_mps <= 0.0 ||
        speed < options_.lateral_velocity_min_speed_mps)
      return false;
    const double turn_radps = log_.imu ? imu_.wz_radps - x_(7) : 0.0;
    if (std::abs(turn_radps) > options_.lateral_velocity_max_turn_radps ||
        std::abs(speed * turn_radps) > options_.lateral_velocity_max_lateral_mps2)
      return false;
    // Linearised, it takes the velocity as known: at the start, before the fixes have found it,
    // its error times the yaw's would turn the update (the ideal circuit's yaw beyond 3 sigma for
    // 4 s).
    if (square(kLinearVelocityShare * speed) < P_(2, 2) + P_(3, 3)) return false;
    ReferenceRowJacobian H;
    const double lateral = reference_lateral_velocity(x_, &H);
    const double R =
        square(options_.lateral_velocity_sigma_mps) +
        square(kCarSideSlipPerLateralS2pm * speed * speed * turn_radps) +
        square((antenna_m_ ? kStatedAntennaPlaceSigmaM : kAntennaPlaceSigmaM) * turn_radps);
    const double S = H.lazyProduct(P_).dot(H) + R;
    const Eigen::Matrix<double, kStates, 1> K = P_.lazyProduct(H.transpose()) / S;
    x_ -= K * lateral;
    P_ = joseph_update_thin(P_, K, H, Eigen::Matrix<double, 1, 1>(R));
    return true;
  }

  const State& state() const { return x_; }
  const Covariance& covariance() const { return P_; }

 private:
  static double square(double v) { return v * v; }
  bool within_gate(const Eigen::Vector2d& innovation, const Eigen::Matrix2d& S_inverse) const {
    return !(options_.gnss_gate_chi2 > 0.0) ||
           innovation.dot(S_inverse * innovation) <= options_.gnss_gate_chi2;
  }
  bool update_antenna_position(const Eigen::Vector2d& fix, const Eigen::Matrix2d& R) {
    Eigen::Matrix<double, 2, kStates> H;
    const Eigen::Vector2d innovation = fix - reference_antenna_position(x_, *antenna_m_, &H);
    const Eigen::Matrix<double, kStates, 2> PHt = P_.lazyProduct(H.transpose());
    const Eigen::Matrix2d S_inverse = (H.lazyProduct(PHt) + R).inverse();
    if (!within_gate(innovation, S_inverse)) return false;
    const Eigen::Matrix<double, kStates, 2> K = PHt * S_inverse;
    x_ += K * innovation;
    P_ = joseph_update_thin(P_, K, H, R);
    return true;
  }
  double gnss_sigma(std::size_t k) const {
    return log_.gnss.sigma_m.empty() ? options_.gnss_sigma_m : log_.gnss.sigma_m[k];
  }

  const Log& log_;
  const ReferenceOptions& options_;
  // The antenna's place where vehicle.yaml states one off the axle; else the fixes are the axle's.
  std::optional<Eigen::Vector2d> antenna_m_ = stated_antenna(log_.vehicle);
  double t_s_{};
  State x_ = State::Zero();
  Covariance P_ = Covariance::Identity();
  ImuSample imu_;        // the sample in effect
  ImuSample imu_slope_;  // its readings' change per second until the next
  double imu_t_s_ = 0.0, imu_span_s_ = 0.0;
};

// Initial yaw without wheel data: the first heading sample; else the course of a straight-line
// fit through a growing window of GNSS fixes, once its displacement is at least 10 m and five
// times its own standard deviation (so fix noise alone never fakes motion).
std::pair<double, double> initial_yaw(const Log& log, std::size_t first_fix,
                                      double default_sigma_m) {
  if (log.heading) {
    const auto& h = *log.heading;
    const auto it = std::lower_bound(h.t_s.begin(), h.t_s.end(), log.gnss.t_s[first_fix]);
    const std::size_t k =
        it == h.t_s.end() ? h.size() - 1 : static_cast<std::size_t>(it - h.t_s.begin());
    return {h.heading_rad[k], 0.3};
  }
  const double t0 = log.gnss.t_s[first_fix];
  double n = 0, st = 0, stt = 0, sx = 0, sy = 0, stx = 0, sty = 0;
  for (std::size_t k = first_fix; k < log.gnss.size(); ++k) {
    const double t = log.gnss.t_s[k] - t0;
    n += 1;
    st += t;
    stt += t * t;
    sx += log.gnss.x_m[k];
    sy += log.gnss.y_m[k];
    stx += t * log.gnss.x_m[k];
    sty += t * log.gnss.y_m[k];
    const double spread = stt - st * st / n;  // sum of (t - mean t)^2
    if (n < 5 || spread <= 0.0) continue;
    const Eigen::Vector2d velocity((stx - st * sx / n) / spread, (sty - st * sy / n) / spread);
    const double sigma_m = log.gnss.sigma_m.empty() ? default_sigma_m : log.gnss.sigma_m[k];
    const double span = t;
    const double displacement = velocity.norm() * span;
    const double displacement_sigma = sigma_m / std::sqrt(spread) * span;
    if (displacement >= 10.0 && displacement >= 5.0 * displacement_sigma) {
      return {std::atan2(velocity.y(), velocity.x()), 0.3};
    }
  }
  throw InsufficientDataError(
      "no heading reference: the log has no heading.csv and GNSS never shows the vehicle moving "
      "10 m beyond its noise, so the reference heading cannot be found");
}

}  // namespace

ReferenceTrajectory compute_reference(const Log& log, const ReferenceOptions& options,
                                      ReferenceCovariance covariance) {
  const bool keep_covariance = covariance == ReferenceCovariance::kKeep;
  const double wheel_begin = log.wheels.t_s.front();
  const auto first_fix_it = std::lower_bound(log.gnss.t_s.begin(), log.gnss.t_s.end(), wheel_begin);
  if (first_fix_it == log.gnss.t_s.end() || *first_fix_it > log.wheels.t_s.back()) {
    throw InsufficientDataError(
        "no GNSS fix inside the wheel time span: no reference can be computed");
  }
  // The speed update reads the Doppler column: its unit is judged first.
  if (options.use_gnss_speed) check_doppler_scale(log, log.vehicle.nominal_params());
  const std::size_t first_fix = static_cast<std::size_t>(first_fix_it - log.gnss.t_s.begin());
  const auto [yaw0, yaw_sigma] = initial_yaw(log, first_fix, options.gnss_sigma_m);

  ReferenceEkf ekf(log, options);
  ekf.initialise(log.gnss.t_s[first_fix],
                 Eigen::Vector2d(log.gnss.x_m[first_fix], log.gnss.y_m[first_fix]), yaw0,
                 yaw_sigma);
  if (log.imu) {
    const auto it =
        std::upper_bound(log.imu->t_s.begin(), log.imu->t_s.end(), log.gnss.t_s[first_fix]);
    if (it != log.imu->t_s.begin())
      ekf.set_imu(static_cast<std::size_t>(it - log.imu->t_s.begin()) - 1);
  }

  ReferenceTrajectory reference;
  reference.poses.reserve(log.wheels.size());
  if (keep_covariance) reference.covariance.reserve(log.wheels.size());
  reference.heading_source = log.heading ? "heading.csv" : "GNSS course";
  const bool smooth = options.mode == ReferenceMode::kSmoother;
  // Per node of the timeline: filtered and predicted state/covariance and the transition into it.
  std::vector<State> filtered_x, predicted_x;
  std::vector<Covariance> filtered_P, predicted_P, transition;
  std::vector<std::size_t> wheel_node;  // smoother only: the node of each wheel sample
  SensorEventMerge events(log, log.gnss.t_s[first_fix]);
  if (smooth) {  // 8x8 matrices per node: reserved once instead of grown
    const std::size_t nodes = events.remaining();
    for (auto* v : {&filtered_x, &predicted_x}) v->reserve(nodes);
    for (auto* v : {&filtered_P, &predicted_P, &transition}) v->reserve(nodes);
    wheel_node.reserve(log.wheels.size());
  }
  bool first_fix_consumed = false;
  while (const std::optional<SensorEvent> next = events.next()) {
    const SensorEvent& event = *next;
    const Covariance F = ekf.predict(event.t_s);
    if (smooth) {
      predicted_x.push_back(ekf.state());
      predicted_P.push_back(ekf.covariance());
      transition.push_back(F);
    }
    switch (event.kind) {
      case SensorEventKind::kImu:
        ekf.set_imu(event.index);
        break;
      case SensorEventKind::kGnss:
        if (event.index == first_fix && !first_fix_consumed) {
          first_fix_consumed = true;  // it initialised the filter
          ++reference.gnss_used;
        } else if (ekf.update_gnss(event.index)) {
          ++reference.gnss_used;
          if (options.use_gnss_speed && !log.gnss.speed_mps.empty())
            ekf.update_speed(log.gnss.speed_mps[event.index]);
          // The constraint holds the velocity's course to yaw where it applies; elsewhere,
          // without heading.csv, the course is the heading's only absolute measurement.
          if (!ekf.update_lateral_velocity() && !log.heading) ekf.update_course();
        } else {
          ++reference.gnss_rejected;
        }
        break;
      case SensorEventKind::kHeading:
        ekf.update_yaw(log.heading->heading_rad[event.index], options.heading_sigma_rad);
        break;
      case SensorEventKind::kWheel:
        if (reference.poses.size() == 0) reference.first_wheel_index = event.index;
        if (smooth) wheel_node.push_back(filtered_x.size());
        reference.poses.emplace_back(ekf.state()(0), ekf.state()(1), ekf.state()(4));
        if (keep_covariance) {
          reference.covariance.push_back((Eigen::Matrix3d() << ekf.covariance().block<2, 2>(0, 0),
                                          ekf.covariance().block<2, 1>(0, 4),
                                          ekf.covariance().block<1, 2>(4, 0),
                                          ekf.covariance()(4, 4))
                                             .finished());
        }
        break;
    }
    if (smooth) {
      filtered_x.push_back(ekf.state());
      filtered_P.push_back(ekf.covariance());
    }
  }
  if (reference.poses.size() < 2) {
    throw InsufficientDataError("the reference covers fewer than 2 wheel samples");
  }
  if (!smooth) return reference;

  // Rauch-Tung-Striebel backward pass over every node.
  std::vector<State> smoothed_x = filtered_x;
  std::vector<Covariance> smoothed_P = filtered_P;
  for (std::size_t n = filtered_x.size() - 1; n-- > 0;) {
    const Covariance C =
        predicted_P[n + 1].llt().solve(transition[n + 1].lazyProduct(filtered_P[n])).transpose();
    State difference = smoothed_x[n + 1] - predicted_x[n + 1];
    smoothed_x[n] = filtered_x[n] + C * difference;
    smoothed_P[n] =
        filtered_P[n] +
        C.lazyProduct(smoothed_P[n + 1] - predicted_P[n + 1]).eval().lazyProduct(C.transpose());
  }
  for (std::size_t i = 0; i < wheel_node.size(); ++i) {
    const auto& x = smoothed_x[wheel_node[i]];
    const auto& P = smoothed_P[wheel_node[i]];
    reference.poses[i] = Pose2(x(0), x(1), x(4));
    if (keep_covariance) {
      reference.covariance[i] << P.block<2, 2>(0, 0), P.block<2, 1>(0, 4), P.block<1, 2>(4, 0),
          P(4, 4);
    }
  }
  return reference;
}

}  // namespace odocal
