// wheels.csv's drive_force_n: read where given, and refused where it cannot be the tyres' force
// (a value beyond 3 g, a force in kN, its sign turned, another clock, no brakes in it), named by
// file and column.
// The simulator writes it when asked, as a car's bus would give it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../support/temp_log_dir.hpp"
#include "odocal/error.hpp"
#include "odocal/io/log_reader.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/model/gravity.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

using testing::TempLogDir;

TEST(DriveForceColumn, IsReadWhereWheelsCsvGivesIt) {
  const TempLogDir dir;
  dir.write("wheels.csv",
            "t,rl_ticks,rr_ticks,drive_force_n\n0,0,0,0\n1,48,48,150.5\n2,96,96,-300\n");
  const Log log = read_log(dir.path());
  ASSERT_EQ(log.wheels.drive_force_n.size(), 3u);
  EXPECT_DOUBLE_EQ(log.wheels.drive_force_n[1], 150.5);
  EXPECT_DOUBLE_EQ(log.wheels.drive_force_n[2], -300.0);
  // Without the column: none, as before.
  const TempLogDir plain;
  EXPECT_TRUE(read_log(plain.path()).wheels.drive_force_n.empty());
}

TEST(DriveForceColumn, AValueBeyondThreeGravitiesForTheBodysMassIsRefusedWhereItIs) {
  const TempLogDir dir;
  // 1500 kg at 3 g is 44 130 N: a torque of 50 000 N m is not a force.
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks,drive_force_n\n0,0,0,0\n1,48,48,50000\n2,96,96,0\n");
  try {
    read_log(dir.path());
    FAIL() << "a force beyond 3 g was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().file, dir.file("wheels.csv"));
    EXPECT_EQ(e.location().line, 3u);
    EXPECT_EQ(e.location().field, "drive_force_n");
    EXPECT_NE(e.problem().find("3 g"), std::string::npos) << e.what();
  }
}

TEST(DriveForceColumn, ANonFiniteValueIsRefusedWhereItIs) {
  const TempLogDir dir;
  dir.write("wheels.csv", "t,rl_ticks,rr_ticks,drive_force_n\n0,0,0,0\n1,48,48,nan\n2,96,96,0\n");
  try {
    read_log(dir.path());
    FAIL() << "NaN was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().line, 3u);
    EXPECT_EQ(e.location().field, "drive_force_n");
  }
}

// One lap of the built-in circuit, realistic and rear-driven, with the force column.
sim::SimulatedDrive lap_with_force(double sigma_n = 100.0) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.route.laps = 1;
  scenario.wheels.drive_force_sigma_n = sigma_n;
  return sim::simulate(scenario);
}

TEST(DriveForceColumn, TheSimulatorWritesTheTyresForceAtTheWheelsSamples) {
  const sim::SimulatedDrive drive = lap_with_force(0.0);
  ASSERT_EQ(drive.wheel_drive_force_n.size(), drive.wheel_t_s.size());
  // Noise-free, what is left of the force beyond drag and rolling resistance is the mass times
  // the accelerometer's forward reading less its noise, wherever the car drives straight (a
  // turn's steered front wheels and side slip take some of it sideways): within the
  // accelerometer's noise of 0.2 m/s^2 on average over the lap.
  const sim::Scenario scenario = load_scenario("circuit");
  const sim::VehicleDynamicsConfig& car = scenario.dynamics;
  const Log log = simulated_log(drive, true);
  double sum = 0.0;
  int compared = 0;
  for (std::size_t k = 1; k + 1 < log.wheels.size(); ++k) {
    const double dt = log.wheels.t_s[k + 1] - log.wheels.t_s[k - 1];
    const double speed =
        (log.wheels.rev_rl[k] + log.wheels.rev_rl[k + 1]) * log.vehicle.circumference_rl_m / dt;
    if (speed < 5.0) continue;
    const double resistance = 0.5 * car.air_density_kgpm3 * car.drag_area_m2 * speed * speed +
                              car.rolling_resistance * car.mass_kg * kGravityMps2;
    const double from_force = (drive.wheel_drive_force_n[k] - resistance) / car.mass_kg;
    const std::size_t i = std::min(k, drive.imu.size() - 1);  // both at 50 Hz from t = 0
    if (std::abs(drive.imu.ay_mps2[i]) > 0.5) continue;
    sum += from_force - drive.imu.ax_mps2[i];
    ++compared;
  }
  ASSERT_GT(compared, 1000);
  EXPECT_LT(std::abs(sum / compared), 0.1);
  // The ideal vehicle has no tyre forces to report.
  sim::Scenario ideal = scenario;
  ideal.ideal = true;
  ideal.route.laps = 1;
  ideal.wheels.drive_force_sigma_n = 100.0;
  EXPECT_THROW(sim::simulate(ideal), InputError);
}

TEST(DriveForceColumn, SurvivesTheLogDirectory) {
  const TempLogDir dir;
  const sim::SimulatedDrive drive = lap_with_force();
  const sim::Scenario scenario = [] {
    sim::Scenario s = load_scenario("circuit");
    s.route.laps = 1;
    s.wheels.drive_force_sigma_n = 100.0;
    return s;
  }();
  write_simulated_log(drive, scenario, dir.path());
  const Log log = read_log(dir.path());
  ASSERT_EQ(log.wheels.drive_force_n.size(), drive.wheel_drive_force_n.size());
  for (std::size_t k = 0; k < log.wheels.size(); k += 997)
    EXPECT_NEAR(log.wheels.drive_force_n[k], drive.wheel_drive_force_n[k], 0.05);
  // The scenario file says how it was made.
  EXPECT_DOUBLE_EQ(
      load_scenario((dir.path() / "scenario.yaml").string()).wheels.drive_force_sigma_n, 100.0);
}

// The simulated lap's force column changed by `fault`, read as a log reads it.
template <class Fault>
std::string refusal_of(Fault fault) {
  sim::SimulatedDrive drive = lap_with_force();
  fault(drive.wheel_drive_force_n);
  try {
    simulated_log(drive);
  } catch (const InputError& e) {
    EXPECT_EQ(e.location().file, "wheels.csv");
    EXPECT_EQ(e.location().field, "drive_force_n");
    return e.problem();
  }
  return "";
}

TEST(DriveForceColumn, AForceInAnotherUnitWithItsSignTurnedOrLateIsRefused) {
  // As simulated: read.
  EXPECT_EQ(refusal_of([](std::vector<double>&) {}), "");
  // A mass 15 % off the body's (or a torque map's error) is a scale the slip coefficients take.
  EXPECT_EQ(refusal_of([](std::vector<double>& f) {
              for (double& v : f) v *= 0.85;
            }),
            "");
  const std::string kilonewtons = refusal_of([](std::vector<double>& f) {
    for (double& v : f) v /= 1000.0;
  });
  EXPECT_NE(kilonewtons.find("kN"), std::string::npos) << kilonewtons;
  const std::string turned = refusal_of([](std::vector<double>& f) {
    for (double& v : f) v = -v;
  });
  EXPECT_NE(turned.find("sign turned"), std::string::npos) << turned;
  const std::string late = refusal_of([](std::vector<double>& f) {
    std::rotate(f.begin(), f.end() - 250, f.end());  // 5 s late at 50 Hz
  });
  EXPECT_NE(late.find("another clock"), std::string::npos) << late;
  // A column that never changes (a signal the bus did not fill) follows nothing.
  const std::string constant = refusal_of([](std::vector<double>& f) {
    for (double& v : f) v = 500.0;
  });
  EXPECT_NE(constant.find("hardly follows"), std::string::npos) << constant;
  // The engine's drive torque without the brakes': right while driving on, nothing while braking
  // (the lap drives forward only). Over the whole lap it reads 0.43 of the wheels' acceleration,
  // which the gain check would blame on a unit.
  const std::string drive_only = refusal_of([](std::vector<double>& f) {
    for (double& v : f) v = std::max(v, 0.0);
  });
  EXPECT_NE(drive_only.find("hardly brakes"), std::string::npos) << drive_only;
}

}  // namespace
}  // namespace odocal
