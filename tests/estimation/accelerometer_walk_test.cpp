// The heading walk that the accelerometer's noise makes through a tyre model, against Monte Carlo
// dead reckoning of one drive with many draws of that noise; and the noise estimate against
// known white noise under a slow signal.

#include "odocal/estimation/accelerometer_walk.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "odocal/estimation/driving_state.hpp"
#include "odocal/model/gravity.hpp"

namespace odocal {
namespace {

constexpr double kTrack = 1.6;
constexpr double kCircumference = 2.0;
constexpr double kDt = 0.02;

double speed_at(double t) { return 15.0 + 3.0 * std::sin(0.3 * t); }
double acceleration_at(double t) { return 0.9 * std::cos(0.3 * t); }
double yaw_rate_at(double t) { return 0.2 * std::sin(0.1 * t); }

// A drive that speeds up, brakes and turns both ways, with its wheels' exact increments and an
// accelerometer at the wheels' rate or at every `imu_every`-th wheel sample.
struct Drive {
  WheelStream wheels;
  ImuStream imu;
};
Drive drive(double duration_s, int imu_every = 1) {
  Drive d;
  for (int k = 0; k * kDt <= duration_s + 1e-9; ++k) {
    const double t = k * kDt, mid = t - 0.5 * kDt;
    d.wheels.t_s.push_back(t);
    const double v = speed_at(mid), w = yaw_rate_at(mid);
    d.wheels.rev_rl.push_back(k == 0 ? 0.0 : (v - 0.5 * kTrack * w) * kDt / kCircumference);
    d.wheels.rev_rr.push_back(k == 0 ? 0.0 : (v + 0.5 * kTrack * w) * kDt / kCircumference);
    if (k % imu_every != 0) continue;
    d.imu.t_s.push_back(t);
    d.imu.ax_mps2.push_back(acceleration_at(t));
    d.imu.ay_mps2.push_back(speed_at(t) * yaw_rate_at(t));
    d.imu.wz_radps.push_back(yaw_rate_at(t));
  }
  return d;
}

OdometryParams params() { return {kCircumference, kCircumference, kTrack}; }

TyreModel physical() {
  TyreModel model;
  model.k_load_s2pm = 2e-3;
  model.k_drive_slip = 0.05;
  model.k_brake_slip = 0.02;
  return model;
}

VehicleBody rear_driven() {
  VehicleBody body;
  body.track_width_m = kTrack;
  body.drivetrain = Drivetrain::kRear;
  return body;
}

// The heading at the drive's end, dead-reckoned with the model at the states `imu` gives.
double final_heading(const WheelStream& wheels, const ImuStream& imu, const TyreModel& model,
                     const VehicleBody& body) {
  const auto states = driving_states(wheels, &imu, params());
  const WheelStream counted = with_tyre_model(wheels, states, model, body);
  double heading = 0.0;
  for (std::size_t k = 1; k < counted.size(); ++k)
    heading += body_increment({counted.rev_rl[k], counted.rev_rr[k]}, params()).yaw_rad;
  return heading;
}

ImuStream with_noise(ImuStream imu, double sigma, std::mt19937& random) {
  std::normal_distribution<double> noise(0.0, sigma);
  for (double& a : imu.ax_mps2) a += noise(random);
  for (double& a : imu.ay_mps2) a += noise(random);
  return imu;
}

TEST(AccelerometerWalk, NoiseEstimateFindsWhiteNoiseUnderASlowSignal) {
  std::mt19937 random(7);
  const Drive d = drive(300.0);
  const ImuStream noisy = with_noise(d.imu, 0.2, random);
  EXPECT_NEAR(white_noise_sigma(noisy.ax_mps2), 0.2, 0.01);
  EXPECT_NEAR(white_noise_sigma(noisy.ay_mps2), 0.2, 0.01);
  EXPECT_LT(white_noise_sigma(d.imu.ay_mps2), 1e-3);  // the signal alone
  EXPECT_EQ(white_noise_sigma({1.0, 2.0}), 0.0);
  // A long drive's channel, whose differences are taken at a stride.
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<double> long_channel(1000000);
  for (std::size_t k = 0; k < long_channel.size(); ++k)
    long_channel[k] = std::sin(1e-3 * static_cast<double>(k)) + noise(random);
  EXPECT_NEAR(white_noise_sigma(long_channel), 0.05, 0.0015);
}

// The stated walk against the scatter of the final heading over draws of the noise.
void expect_walk_predicts_scatter(int imu_every) {
  const Drive d = drive(200.0, imu_every);
  const TyreModel model = physical();
  const VehicleBody body = rear_driven();
  const double exact = final_heading(d.wheels, d.imu, model, body);
  std::mt19937 random(11);
  constexpr int kDraws = 300;
  constexpr double kNoise = 0.2;
  double sum_squares = 0.0;
  for (int draw = 0; draw < kDraws; ++draw) {
    const double error =
        final_heading(d.wheels, with_noise(d.imu, kNoise, random), model, body) - exact;
    sum_squares += error * error;
  }
  const double scatter = std::sqrt(sum_squares / kDraws);
  const AccelerometerWalk walk =
      accelerometer_heading_walk(d.wheels, with_noise(d.imu, kNoise, random),
                                 driving_states(d.wheels, &d.imu, params()), model, body, params());
  EXPECT_NEAR(walk.noise_y_mps2, kNoise, 0.02);
  ASSERT_GT(scatter, 1e-4);  // a walk worth predicting: 0.1 mrad at least
  // 300 draws measure a standard deviation to about 4 % (1 sigma).
  EXPECT_NEAR(walk.heading_rad / scatter, 1.0, 0.15) << walk.heading_rad << " vs " << scatter;
}

// The tyres' force at each wheel row, as a car's bus would give it (a rear-driven body's).
void give_the_force(Drive& d) {
  const VehicleBody body = rear_driven();
  for (const double t : d.wheels.t_s) {
    const double v = speed_at(t), w = yaw_rate_at(t);
    d.wheels.drive_force_n.push_back(
        body.mass_kg * (acceleration_at(t) + body.rolling_resistance * kGravityMps2 +
                        (1.0 - body.rear_axle_load_share) * body.wheelbase_m * w * w) +
        0.5 * 1.2 * body.drag_area_m2 * v * v);
  }
}

TEST(AccelerometerWalk, WhereTheLogGivesTheForceOnlyTheLateralChannelWalks) {
  Drive d = drive(200.0);
  const TyreModel model = physical();
  const VehicleBody body = rear_driven();
  std::mt19937 random(5);
  const ImuStream noisy = with_noise(d.imu, 0.2, random);
  const AccelerometerWalk read = accelerometer_heading_walk(
      d.wheels, noisy, driving_states(d.wheels, &d.imu, params()), model, body, params());
  give_the_force(d);
  const AccelerometerWalk given = accelerometer_heading_walk(
      d.wheels, noisy, driving_states(d.wheels, &d.imu, params()), model, body, params());
  EXPECT_FALSE(read.forward_force_given);
  EXPECT_TRUE(given.forward_force_given);
  EXPECT_LT(given.heading_rad, read.heading_rad);
  // The same Monte Carlo as above: the forward noise moves nothing, the lateral one what it says.
  const double exact = final_heading(d.wheels, d.imu, model, body);
  double sum_squares = 0.0;
  constexpr int kDraws = 300;
  for (int draw = 0; draw < kDraws; ++draw) {
    const double error =
        final_heading(d.wheels, with_noise(d.imu, 0.2, random), model, body) - exact;
    sum_squares += error * error;
  }
  EXPECT_NEAR(given.heading_rad / std::sqrt(sum_squares / kDraws), 1.0, 0.15);
}

TEST(AccelerometerWalk, PredictsTheHeadingScatterOfNoisyDeadReckoning) {
  expect_walk_predicts_scatter(1);
}

TEST(AccelerometerWalk, PredictsItWhereTheAccelerometerIsSlowerThanTheWheels) {
  // Every fourth wheel sample: the states between take an interpolation of two samples.
  expect_walk_predicts_scatter(4);
}

TEST(AccelerometerWalk, PlainModelAndNoAccelerometerSampleWalkNothing) {
  const Drive d = drive(20.0);
  const auto states = driving_states(d.wheels, &d.imu, params());
  EXPECT_EQ(
      accelerometer_heading_walk(d.wheels, d.imu, states, TyreModel{}, rear_driven(), params())
          .heading_rad,
      0.0);
  // An accelerometer that ends before the wheels start: no wheel sample takes its force.
  ImuStream before = d.imu;
  for (double& t : before.t_s) t -= 100.0;
  EXPECT_EQ(
      accelerometer_heading_walk(d.wheels, before, states, physical(), rear_driven(), params())
          .heading_rad,
      0.0);
}

TEST(AccelerometerWalk, RejectsStatesThatDoNotMatchTheWheels) {
  const Drive d = drive(5.0);
  EXPECT_THROW(accelerometer_heading_walk(d.wheels, d.imu, {}, physical(), rear_driven(), params()),
               std::invalid_argument);
}

}  // namespace
}  // namespace odocal
