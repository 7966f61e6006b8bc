// The doctor's check of the GNSS antenna's side of the car (gnss.place): an antenna y left of the
// rear axle's centre runs y w slower in a left turn, which a Doppler column shows. Simulated
// drives with the antenna moved, stated in vehicle.yaml or not.

#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "odocal/estimation/log_diagnosis.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

struct Antenna {
  double ahead_m{}, left_m{};
  bool stated = false;
  bool ideal = false;
};

Log drive_with_doppler(const std::string& scenario_name, const Antenna& antenna) {
  sim::Scenario scenario = load_scenario(scenario_name);
  scenario.route.laps = 1;
  scenario.ideal = antenna.ideal;
  scenario.seeds.noise = 3;
  scenario.gnss.speed_sigma_mps = 0.05;
  scenario.gnss.lever_arm_x_m = antenna.ahead_m;
  scenario.gnss.lever_arm_y_m = antenna.left_m;
  scenario.gnss.lever_arm_stated = antenna.stated;
  return simulated_log(sim::simulate(scenario));
}

std::optional<Finding> place_finding(const Log& log) {
  for (const Finding& f : diagnose_log(log).findings)
    if (f.check == "gnss.place") return f;
  return std::nullopt;
}

TEST(DoctorAntenna, AnAntennaOffTheCentrelineIsFoundUnlessVehicleYamlStatesIt) {
  for (const std::string scenario : {"urban", "parking"}) {
    const std::optional<Finding> found =
        place_finding(drive_with_doppler(scenario, {.left_m = 0.5}));
    ASSERT_TRUE(found) << scenario;
    EXPECT_EQ(found->severity, FindingSeverity::kWarning);
    EXPECT_NE(found->what.find("0.5 m left of the rear axle's centre"), std::string::npos)
        << found->what << " / " << found->evidence;
    EXPECT_NE(found->fix.find("gnss_y_m: 0.5"), std::string::npos) << found->fix;
    EXPECT_FALSE(place_finding(drive_with_doppler(scenario, {.left_m = 0.5, .stated = true})))
        << scenario;
    EXPECT_FALSE(place_finding(drive_with_doppler(scenario, {.left_m = -0.1}))) << scenario;
  }
}

TEST(DoctorAntenna, ASideStatedWhereTheAntennaIsNotIsFound) {
  Log log = drive_with_doppler("urban", {.ideal = true});
  log.vehicle.gnss_position_m = Eigen::Vector2d(0.0, 0.6);
  const std::optional<Finding> found = place_finding(log);
  ASSERT_TRUE(found);
  EXPECT_NE(found->what.find("on the car's centreline"), std::string::npos) << found->what;
  EXPECT_NE(found->cause.find("gnss_y_m is not where"), std::string::npos) << found->cause;
}

// Ahead of the axle the antenna swings out in the turns, which a Doppler speed shows to second
// order and either way of turning alike: no side is read from it, stated or not.
TEST(DoctorAntenna, AnAntennaAheadOfTheAxleReadsNoSide) {
  EXPECT_FALSE(place_finding(drive_with_doppler("urban", {.ahead_m = 1.5})));
  EXPECT_FALSE(place_finding(drive_with_doppler("urban", {.ahead_m = 1.5, .stated = true})));
  EXPECT_FALSE(place_finding(drive_with_doppler("circuit", {.ahead_m = 1.5})));
}

}  // namespace
}  // namespace odocal
