// The driving state measured from a log against closed-form motions: a circle at constant speed
// and a straight line at constant acceleration; the gyro's turn preferred to the wheels'.

#include "odocal/estimation/driving_state.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace odocal {
namespace {

constexpr double kTrack = 1.6;
constexpr double kCircumference = 2.0;

// Wheels of a motion with speed v(t) and yaw rate w(t), sampled at 100 Hz (exact increments
// from the midpoint rule, which is exact for these polynomials to first order in dt).
Log log_of(double duration_s, double (*speed)(double), double (*yaw_rate)(double)) {
  Log log;
  log.vehicle.track_width_m = kTrack;
  log.vehicle.circumference_rl_m = kCircumference;
  log.vehicle.circumference_rr_m = kCircumference;
  const double dt = 0.01;
  for (int k = 0; k * dt <= duration_s + 1e-9; ++k) {
    const double t = k * dt;
    log.wheels.t_s.push_back(t);
    if (k == 0) {
      log.wheels.rev_rl.push_back(0.0);
      log.wheels.rev_rr.push_back(0.0);
      continue;
    }
    const double mid = t - 0.5 * dt;
    const double v = speed(mid), w = yaw_rate(mid);
    log.wheels.rev_rl.push_back((v - 0.5 * kTrack * w) * dt / kCircumference);
    log.wheels.rev_rr.push_back((v + 0.5 * kTrack * w) * dt / kCircumference);
  }
  return log;
}

TEST(DrivingState, CircleAtConstantSpeedHasOnlyLateralAcceleration) {
  const Log log = log_of(
      10.0, [](double) { return 12.0; }, [](double) { return 0.25; });
  const auto states = driving_states(log, log.vehicle.nominal_params());
  ASSERT_EQ(states.size(), log.wheels.size());
  for (std::size_t k = 100; k < states.size() - 100; k += 37) {
    EXPECT_NEAR(states[k].speed_mps, 12.0, 1e-5);      // single precision
    EXPECT_NEAR(states[k].lateral_mps2(), 3.0, 1e-5);  // v w, to the left
    EXPECT_NEAR(states[k].longitudinal_mps2, 0.0, 1e-5);
    // Without an accelerometer the specific force is the wheels' acceleration.
    EXPECT_EQ(states[k].specific_force_x_mps2, states[k].longitudinal_mps2);
    EXPECT_NEAR(states[k].specific_force_y_mps2, states[k].lateral_mps2(), 1e-5);
  }
}

TEST(DrivingState, TakesTheLogsForceOverEachIncrement) {
  Log log = log_of(
      2.0, [](double) { return 10.0; }, [](double) { return 0.0; });
  EXPECT_FALSE(driving_states(log, log.vehicle.nominal_params())[50].force_given());
  for (std::size_t k = 0; k < log.wheels.size(); ++k)
    log.wheels.drive_force_n.push_back(100.0 * static_cast<double>(k));
  // A row not known (a block of a long log without the column) leaves the accelerometer's.
  log.wheels.drive_force_n[120] = std::nan("");
  const auto states = driving_states(log, log.vehicle.nominal_params());
  EXPECT_FLOAT_EQ(states[0].drive_force_n, 0.0f);
  EXPECT_FLOAT_EQ(states[50].drive_force_n, 4950.0f);  // the trapezoid of rows 49 and 50
  EXPECT_FALSE(states[120].force_given());
  EXPECT_FALSE(states[121].force_given());
  EXPECT_FLOAT_EQ(states[122].drive_force_n, 12150.0f);
}

TEST(DrivingState, StraightAccelerationIsMeasuredFromTheWheels) {
  const Log log = log_of(
      10.0, [](double t) { return 2.0 + 1.5 * t; }, [](double) { return 0.0; });
  const auto states = driving_states(log, log.vehicle.nominal_params());
  for (std::size_t k = 100; k < states.size() - 100; k += 37) {
    EXPECT_NEAR(states[k].speed_mps, 2.0 + 1.5 * log.wheels.t_s[k], 1e-5);
    EXPECT_NEAR(states[k].longitudinal_mps2, 1.5, 1e-5);
    EXPECT_NEAR(states[k].lateral_mps2(), 0.0, 1e-12);
  }
}

void add_gyro(Log& log, double yaw_rate_radps, double ax_mps2 = 0.0, double ay_mps2 = 0.0) {
  log.imu = ImuStream{};
  for (std::size_t k = 0; k < log.wheels.size(); ++k) {
    log.imu->t_s.push_back(log.wheels.t_s[k]);
    log.imu->ax_mps2.push_back(ax_mps2);
    log.imu->ay_mps2.push_back(ay_mps2);
    log.imu->wz_radps.push_back(yaw_rate_radps);
  }
}

TEST(DrivingState, PrefersTheGyroTurnToTheWheels) {
  // Wheels that report no turn while the gyro turns at 0.1 rad/s: the lateral acceleration is
  // the gyro's (the wheels' own turn is what the tyre model corrects).
  Log log = log_of(
      10.0, [](double) { return 10.0; }, [](double) { return 0.0; });
  add_gyro(log, 0.1);
  const auto states = driving_states(log, log.vehicle.nominal_params());
  EXPECT_NEAR(states[500].lateral_mps2(), 1.0, 1e-6);
}

TEST(DrivingState, YawAccelerationIsTheTurnsChangeFromTheGyroOrTheWheels) {
  // A turn tightening at 0.02 rad/s^2: the wheels' own turn says so, and where a gyro measures, it
  // does (here a gyro tightening twice as fast, which the wheels do not).
  Log log = log_of(
      10.0, [](double) { return 10.0; }, [](double t) { return 0.05 + 0.02 * t; });
  const auto from_wheels = driving_states(log, log.vehicle.nominal_params());
  for (std::size_t k = 100; k < log.wheels.size() - 100; k += 37)
    EXPECT_NEAR(from_wheels[k].yaw_acceleration_radps2, 0.02, 1e-5) << k;
  add_gyro(log, 0.0);
  for (std::size_t k = 0; k < log.wheels.size(); ++k)
    log.imu->wz_radps[k] = 0.04 * log.wheels.t_s[k];
  const auto from_gyro = driving_states(log, log.vehicle.nominal_params());
  EXPECT_NEAR(from_gyro[500].yaw_acceleration_radps2, 0.04, 1e-5);
}

TEST(DrivingState, SpecificForceIsTheAccelerometersWhereItMeasures) {
  // Wheels at a constant 10 m/s on a slope: the accelerometer feels gravity's share (what the
  // drive force pushes against), the wheels no acceleration. Before the IMU starts, the wheels'
  // state stands in.
  Log log = log_of(
      10.0, [](double) { return 10.0; }, [](double) { return 0.0; });
  add_gyro(log, 0.05, 0.49, 0.7);
  const std::size_t late = 400;  // IMU from 4 s on
  log.imu->t_s.erase(log.imu->t_s.begin(), log.imu->t_s.begin() + late);
  log.imu->ax_mps2.erase(log.imu->ax_mps2.begin(), log.imu->ax_mps2.begin() + late);
  log.imu->ay_mps2.erase(log.imu->ay_mps2.begin(), log.imu->ay_mps2.begin() + late);
  log.imu->wz_radps.erase(log.imu->wz_radps.begin(), log.imu->wz_radps.begin() + late);
  const auto states = driving_states(log, log.vehicle.nominal_params());
  EXPECT_NEAR(states[700].specific_force_x_mps2, 0.49, 1e-6);
  EXPECT_NEAR(states[700].specific_force_y_mps2, 0.7, 1e-6);
  EXPECT_NEAR(states[700].longitudinal_mps2, 0.0, 1e-5);
  EXPECT_NEAR(states[700].lateral_mps2(), 0.5, 1e-5);  // v times the gyro's rate
  EXPECT_NEAR(states[200].specific_force_x_mps2, 0.0, 1e-5);
  EXPECT_NEAR(states[200].specific_force_y_mps2, 0.0, 1e-5);  // the wheels turn nowhere
}

TEST(DrivingState, TheSlopeThatTheProjectionKnowsAddsToTheForceWithOrWithoutAnAccelerometer) {
  // A 5 % climb at constant speed, the grade beside the wheels as the hills' projection leaves it
  // (the accelerometer, where there is one, then reads the horizontal acceleration: none): the
  // tyres push against g sin(pitch) all the same.
  Log log = log_of(
      10.0, [](double) { return 10.0; }, [](double) { return 0.0; });
  log.wheels.grade.assign(log.wheels.size(), 0.05F);
  const double slope = 9.81 * 0.05 / std::sqrt(1.0 + 0.05 * 0.05);
  const auto without_imu = driving_states(log, log.vehicle.nominal_params());
  EXPECT_NEAR(without_imu[500].specific_force_x_mps2, slope, 1e-5);
  EXPECT_NEAR(without_imu[500].longitudinal_mps2, 0.0, 1e-5);
  add_gyro(log, 0.0, 0.3);
  const auto with_imu = driving_states(log, log.vehicle.nominal_params());
  EXPECT_NEAR(with_imu[500].specific_force_x_mps2, 0.3 + slope, 1e-5);
}

TEST(DrivingState, PlainTyreModelLeavesTheWheelsAlone) {
  const Log log = log_of(
      5.0, [](double t) { return 3.0 + t; }, [](double) { return 0.2; });
  const WheelStream same = with_tyre_model(log, log.vehicle.nominal_params(), TyreModel{});
  EXPECT_EQ(same.rev_rl, log.wheels.rev_rl);
  EXPECT_EQ(same.rev_rr, log.wheels.rev_rr);
}

TEST(DrivingState, LateralCoefficientMakesTheOuterWheelRollShorter) {
  // A left turn: the right wheel is outer, loaded, and rolls a shorter circumference, so it
  // needs more revolutions than the plain model says for the same ground distance: with the
  // model applied, each of its revolutions counts for less ground. (The gyro fixes a_y: without
  // it, the turn would be the corrected wheels' own.)
  Log log = log_of(
      5.0, [](double) { return 10.0; }, [](double) { return 0.3; });
  add_gyro(log, 0.3);
  TyreModel model;
  model.k_lateral_s2pm = 1e-3;
  const WheelStream scaled = with_tyre_model(log, log.vehicle.nominal_params(), model);
  // (To second order: the corrected wheels' mean speed differs by 3e-3 of their difference.)
  EXPECT_NEAR(scaled.rev_rl[250] / log.wheels.rev_rl[250], 1.0 + 3e-3, 1e-6);
  EXPECT_NEAR(scaled.rev_rr[250] / log.wheels.rev_rr[250], 1.0 - 3e-3, 1e-6);
}

TEST(DrivingState, StatesOfTheCountedWheelsNeedNoCopyOfTheStream) {
  // The batch measures the state again from the wheels as the model counts them; it does so
  // without copying the stream, and must get what the copy gives, to the bit.
  Log log = log_of(
      5.0, [](double t) { return 3.0 + 2.0 * t; }, [](double t) { return 0.1 * t; });
  add_gyro(log, 0.2);
  TyreModel model;
  model.k_lateral_s2pm = 1e-3;
  model.k_drive_s2pm = 2e-3;
  model.k_speed_s2pm2 = -1e-5;
  const OdometryParams params = log.vehicle.nominal_params();
  const std::vector<DrivingState> first = driving_states(log, params);
  model.k_load_s2pm = 2e-3;
  model.k_drive_slip = 0.05;
  const VehicleBody body = log.vehicle.body_geometry();
  const std::vector<DrivingState> copied =
      driving_states(with_tyre_model(log.wheels, first, model, body), &*log.imu, params);
  const std::vector<DrivingState> counted =
      driving_states(log.wheels, &*log.imu, params, first, model, body);
  ASSERT_EQ(counted.size(), copied.size());
  for (std::size_t k = 0; k < counted.size(); ++k) {
    EXPECT_EQ(counted[k].speed_mps, copied[k].speed_mps) << k;
    EXPECT_EQ(counted[k].longitudinal_mps2, copied[k].longitudinal_mps2) << k;
    EXPECT_EQ(counted[k].lateral_mps2(), copied[k].lateral_mps2()) << k;
    EXPECT_EQ(counted[k].yaw_rate_radps, copied[k].yaw_rate_radps) << k;
    EXPECT_EQ(counted[k].specific_force_x_mps2, copied[k].specific_force_x_mps2) << k;
  }
  EXPECT_NE(counted[250].speed_mps, first[250].speed_mps);  // the model changed something
  EXPECT_THROW(
      driving_states(log.wheels, &*log.imu, params, std::vector<DrivingState>(3), model, body),
      std::invalid_argument);
}

TEST(DrivingState, MeasuredAgainOnThreadsTheStatesAreTheSameToTheBit) {
  // The batch measures the states again on its threads: running sums and running means split
  // into parts must add up in the order one thread adds them. An accelerometer and gyro that
  // vary, starting late and ending early (the wheels' own turn and a_x stand in outside them).
  Log log = log_of(
      30.0, [](double t) { return 8.0 + 3.0 * std::sin(0.4 * t); },
      [](double t) { return 0.2 * std::cos(0.3 * t); });
  log.imu = ImuStream{};
  for (std::size_t k = 150; k + 150 < log.wheels.size(); k += 2) {
    const double t = log.wheels.t_s[k] + 0.003;
    log.imu->t_s.push_back(t);
    log.imu->ax_mps2.push_back(1.2 * std::sin(0.4 * t) + 0.01 * std::sin(37.0 * t));
    log.imu->ay_mps2.push_back(1.6 * std::cos(0.3 * t));
    log.imu->wz_radps.push_back(0.2 * std::cos(0.3 * t) + 1e-3 * std::sin(11.0 * t));
  }
  TyreModel model;
  model.k_load_s2pm = 2e-3;
  model.k_drive_slip = 0.05;
  model.k_brake_slip = 0.02;
  const OdometryParams params = log.vehicle.nominal_params();
  const VehicleBody body = log.vehicle.body_geometry();
  const std::vector<DrivingState> first = driving_states(log, params);
  const auto again = [&](int threads) {
    std::vector<DrivingState> states = first;
    measure_driving_states_again(log.wheels, &*log.imu, params, model, body, states,
                                 kDrivingStateHalfWindowS, threads);
    return states;
  };
  const std::vector<DrivingState> one = again(1);
  for (const int threads : {2, 3, 7}) {
    const std::vector<DrivingState> several = again(threads);
    ASSERT_EQ(several.size(), one.size());
    for (std::size_t k = 0; k < one.size(); ++k) {
      ASSERT_EQ(several[k].speed_mps, one[k].speed_mps) << threads << " threads, sample " << k;
      ASSERT_EQ(several[k].longitudinal_mps2, one[k].longitudinal_mps2) << k;
      ASSERT_EQ(several[k].yaw_rate_radps, one[k].yaw_rate_radps) << k;
      ASSERT_EQ(several[k].yaw_acceleration_radps2, one[k].yaw_acceleration_radps2) << k;
      ASSERT_EQ(several[k].specific_force_x_mps2, one[k].specific_force_x_mps2) << k;
      ASSERT_EQ(several[k].specific_force_y_mps2, one[k].specific_force_y_mps2) << k;
    }
  }
  EXPECT_NE(one[1500].speed_mps, first[1500].speed_mps);  // the model changed something
}

}  // namespace
}  // namespace odocal
