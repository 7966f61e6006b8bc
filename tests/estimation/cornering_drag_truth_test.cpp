// The front tyres' cornering drag (cornering_drag_mps2) against the simulator's own force, where
// it matters: Hockenheim's fast kink, which the circuit's driver takes in a rear-driven car that
// fishtails. With the accelerometer, gyro and force column noise-free, what the tyres push beyond
// the body's forward acceleration, the drag and the rolling resistance is the cornering drag
// (docs/tyre-model.md, "The front tyres' steer").

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "odocal/estimation/driving_state.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/model/tyre_model.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

const std::string kHockenheimTrack =
    std::string(ODOCAL_SOURCE_DIR) + "/../shared/data/tracks/hockenheim/track.csv";

// The mean residual of the kink's driven samples (|f_y| > 6 m/s^2): of the drag along the steered
// wheels, and of the drag along wheels steered by L w / v alone.
struct KinkResidual {
  double steered_mps2{}, along_path_mps2{};
  int samples{};
};

KinkResidual kink_residual(double front_stiffness, double rear_stiffness) {
  sim::Scenario scenario = load_scenario("circuit");
  use_track_file(scenario, kHockenheimTrack);
  scenario.route.laps = 1;
  scenario.imu.acc_sigma_mps2 = 0.0;
  scenario.imu.yaw_rate_sigma_radps = 0.0;
  scenario.wheels.drive_force_sigma_n = 0.0;
  scenario.dynamics.cornering_stiffness_per_load_front = front_stiffness;
  scenario.dynamics.cornering_stiffness_per_load_rear = rear_stiffness;
  const Log log = simulated_log(sim::simulate(scenario));
  VehicleBody body = log.vehicle.body_geometry();  // the simulator's mass, drag and geometry
  body.front_cornering_stiffness = front_stiffness;
  body.rear_cornering_stiffness = rear_stiffness;
  const double b = (1.0 - body.rear_axle_load_share) * body.wheelbase_m;
  KinkResidual out;
  for (const DrivingState& s : driving_states(log, log.vehicle.nominal_params())) {
    const double f_y = s.specific_force_y_mps2, v = s.speed_mps;
    if (!(s.drive_force_n > 0.0f) || v < 5.0 || std::abs(f_y) < 6.0) continue;
    const double cornering =
        s.drive_force_n / body.mass_kg - s.specific_force_x_mps2 - road_resistance(body, v).total();
    out.steered_mps2 += cornering - cornering_drag_mps2(s, body);
    out.along_path_mps2 += cornering - b * f_y * s.yaw_rate_radps / v;
    ++out.samples;
  }
  out.steered_mps2 /= out.samples;
  out.along_path_mps2 /= out.samples;
  return out;
}

TEST(CorneringDragTruth, TheSteeredFrontTyresCarryTheKinksForce) {
  if (!std::filesystem::exists(kHockenheimTrack))
    GTEST_SKIP() << "shared data absent: " << kHockenheimTrack;
  // The simulator's tyres (16 and 19 per rad), then a car that understeers more (12 and 23)
  // stated as it is. Along L w / v the kink's force is missed by 0.115 and 0.068 m/s^2 (measured
  // 2026-12-05); steered by the slip angles that the tyres carry the lateral force and the yaw
  // inertia with, by 0.016 and 0.037. What is left is mostly the fishtail's yaw acceleration,
  // which the gyro gives as a mean over +-0.05 s (the 12/23 car's kink is shorter and sharper).
  struct Case {
    double front, rear, at_most_of_along_path;
  };
  for (const Case& c : {Case{16.0, 19.0, 0.3}, Case{12.0, 23.0, 0.7}}) {
    const KinkResidual r = kink_residual(c.front, c.rear);
    ASSERT_GT(r.samples, 5) << c.front << "/" << c.rear;
    EXPECT_GT(std::abs(r.along_path_mps2), 0.05) << c.front << "/" << c.rear;
    EXPECT_LT(std::abs(r.steered_mps2), c.at_most_of_along_path * std::abs(r.along_path_mps2))
        << c.front << "/" << c.rear;
    EXPECT_LT(std::abs(r.steered_mps2), 0.045) << c.front << "/" << c.rear;
  }
}

}  // namespace
}  // namespace odocal
