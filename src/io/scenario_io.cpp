#include "odocal/io/scenario_io.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "builtin_scenarios.hpp"
#include "odocal/data/physical_limits.hpp"
#include "odocal/io/track_reader.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/sim/centreline_route.hpp"
#include "yaml_map.hpp"

namespace odocal {
namespace {

using detail::YamlMap;
constexpr double kBig = 1e9;

sim::RouteSegment parse_segment(const YAML::Node& node, const std::string& file,
                                std::size_t index) {
  YamlMap map(node, file, fmt::format("route.segments[{}]", index));
  sim::RouteSegment segment;
  bool reverse = false;
  map.read("reverse", reverse);
  map.read("stop_s", segment.stop_dwell_s, 0.0, kBig);
  const int direction = reverse ? -1 : 1;
  segment.geometry.direction = direction;
  int shapes = 0;
  if (map.has("straight")) {
    map.read("straight", segment.geometry.length_m, 1e-3, kBig);
    ++shapes;
  }
  if (auto arc = map.map("arc")) {
    double radius_m = 0.0, turn_deg = 0.0;
    arc->read("radius_m", radius_m, 1e-3, kBig);
    arc->read("turn_deg", turn_deg, -3600.0, 3600.0);
    arc->reject_unknown_keys();
    if (radius_m <= 0.0 || turn_deg == 0.0)
      throw InputError(arc->location(), "an arc needs radius_m > 0 and turn_deg != 0");
    segment.geometry.length_m = radius_m * std::abs(rad_from_deg(turn_deg));
    // Curvature is d(yaw)/d(signed distance): reversing flips its sign for the same yaw change.
    const double curvature = std::copysign(1.0 / radius_m, turn_deg) * direction;
    segment.geometry.curvature_start_1pm = segment.geometry.curvature_end_1pm = curvature;
    ++shapes;
  }
  if (auto clothoid = map.map("clothoid")) {
    clothoid->read("length_m", segment.geometry.length_m, 1e-3, kBig);
    clothoid->read("curvature_start_1pm", segment.geometry.curvature_start_1pm, -10.0, 10.0);
    clothoid->read("curvature_end_1pm", segment.geometry.curvature_end_1pm, -10.0, 10.0);
    clothoid->reject_unknown_keys();
    if (segment.geometry.length_m <= 0.0)
      throw InputError(clothoid->location(), "length_m is required");
    ++shapes;
  }
  map.reject_unknown_keys();
  if (shapes != 1) throw InputError(map.location(), "give exactly one of straight, arc, clothoid");
  return segment;
}

void parse_route(YamlMap route, sim::Route& out) {
  route.read("repeat", out.repeat, 1, 1000);
  route.read("laps", out.laps, 1, 1000);
  if (auto start = route.map("start")) {
    double heading_deg = deg_from_rad(out.start.z());
    start->read("x_m", out.start.x(), -kBig, kBig);
    start->read("y_m", out.start.y(), -kBig, kBig);
    start->read("heading_deg", heading_deg, -360.0, 360.0);
    out.start.z() = rad_from_deg(heading_deg);
    start->reject_unknown_keys();
  }
  if (auto terrain = route.map("terrain")) {
    terrain->read("max_grade", out.terrain.max_grade, 0.0, 0.3);
    terrain->read("wavelength_m", out.terrain.wavelength_m, 10.0, 1e5);
    terrain->reject_unknown_keys();
  }
  const auto segments = route.sequence("segments");
  if (!segments.empty()) out.segments.clear();
  for (std::size_t i = 0; i < segments.size(); ++i)
    out.segments.push_back(parse_segment(segments[i], route.file(), i));
  route.reject_unknown_keys();
}

WheelUnit parse_wheel_unit(YamlMap& map, const std::string& key, WheelUnit fallback) {
  std::string text;
  map.read(key, text);
  if (text.empty()) return fallback;
  if (const auto unit = parse_enum<WheelUnit>(text)) return *unit;
  throw InputError(map.location(key), "expected one of ticks, rad, radps, mps");
}

const char* altitude_name(sim::GnssSimConfig::Altitude altitude) {
  switch (altitude) {
    case sim::GnssSimConfig::Altitude::kAlways:
      return "always";
    case sim::GnssSimConfig::Altitude::kNever:
      return "never";
    case sim::GnssSimConfig::Altitude::kAuto:
      break;
  }
  return "auto";
}

void parse_sensors(YamlMap sensors, sim::Scenario& s) {
  if (auto gnss = sensors.map("gnss")) {
    gnss->read("rate_hz", s.gnss.rate_hz, 0.01, 1000.0);
    gnss->read("sigma_m", s.gnss.sigma_m, 0.0, 1000.0);
    gnss->read("gauss_markov_sigma_m", s.gnss.gauss_markov_sigma_m, 0.0, 1000.0);
    gnss->read("gauss_markov_tau_s", s.gnss.gauss_markov_tau_s, 1e-3, kBig);
    gnss->read("outlier_rate", s.gnss.outlier_rate, 0.0, 1.0);
    gnss->read("outlier_min_m", s.gnss.outlier_min_m, 0.0, 1e6);
    gnss->read("outlier_max_m", s.gnss.outlier_max_m, s.gnss.outlier_min_m, 1e6);
    gnss->read("latency_s", s.gnss.latency_s, 0.0, 10.0);
    gnss->read("lever_arm_x_m", s.gnss.lever_arm_x_m, -100.0, 100.0);
    gnss->read("lever_arm_y_m", s.gnss.lever_arm_y_m, -100.0, 100.0);
    gnss->read("lever_arm_stated", s.gnss.lever_arm_stated);
    gnss->read("altitude_sigma_m", s.gnss.altitude_sigma_m, -1.0, 1e3);
    gnss->read("speed_sigma_mps", s.gnss.speed_sigma_mps, -1.0, 100.0);
    const auto outages = gnss->sequence("outages");
    if (!outages.empty()) s.gnss.outages.clear();
    for (std::size_t i = 0; i < outages.size(); ++i) {
      YamlMap outage(outages[i], gnss->file(), fmt::format("sensors.gnss.outages[{}]", i));
      sim::Outage parsed;
      outage.read("start_s", parsed.start_s, 0.0, kBig);
      outage.read("duration_s", parsed.duration_s, 0.0, kBig);
      outage.reject_unknown_keys();
      s.gnss.outages.push_back(parsed);
    }
    std::string output = s.gnss.output_latlon ? "latlon" : "local";
    gnss->read("output", output);
    if (output != "local" && output != "latlon")
      throw InputError(gnss->location("output"), "expected local or latlon");
    s.gnss.output_latlon = output == "latlon";
    std::string altitude = altitude_name(s.gnss.altitude);
    gnss->read("altitude", altitude);
    if (altitude == "auto")
      s.gnss.altitude = sim::GnssSimConfig::Altitude::kAuto;
    else if (altitude == "always")
      s.gnss.altitude = sim::GnssSimConfig::Altitude::kAlways;
    else if (altitude == "never")
      s.gnss.altitude = sim::GnssSimConfig::Altitude::kNever;
    else
      throw InputError(gnss->location("altitude"), "expected auto, always or never");
    if (auto origin = gnss->map("origin")) {
      origin->read("lat_deg", s.gnss.origin.latitude_deg, -90.0, 90.0);
      origin->read("lon_deg", s.gnss.origin.longitude_deg, -180.0, 180.0);
      origin->read("alt_m", s.gnss.origin.altitude_m, -1e4, 1e5);
      origin->reject_unknown_keys();
    }
    gnss->reject_unknown_keys();
  }
  if (auto imu = sensors.map("imu")) {
    imu->read("rate_hz", s.imu.rate_hz, 0.01, 10000.0);
    imu->read("acc_sigma_mps2", s.imu.acc_sigma_mps2, 0.0, 100.0);
    imu->read("yaw_rate_sigma_radps", s.imu.yaw_rate_sigma_radps, 0.0, 10.0);
    imu->read("gyro_bias_radps", s.imu.gyro_bias_radps, -10.0, 10.0);
    imu->read("mount_x_m", s.imu.mount_x_m, kMountingOffsetM.min, kMountingOffsetM.max);
    imu->read("mount_y_m", s.imu.mount_y_m, kMountingOffsetM.min, kMountingOffsetM.max);
    imu->reject_unknown_keys();
  }
  if (auto heading = sensors.map("heading")) {
    heading->read("rate_hz", s.heading.rate_hz, 0.01, 10000.0);
    heading->read("sigma_rad", s.heading.sigma_rad, 0.0, 10.0);
    heading->read("bias_rad", s.heading.bias_rad, -10.0, 10.0);
    heading->reject_unknown_keys();
  }
  if (auto wheels = sensors.map("wheels")) {
    wheels->read("rate_hz", s.wheels.rate_hz, 0.01, 10000.0);
    s.wheels.output = parse_wheel_unit(*wheels, "output", s.wheels.output);
    wheels->read("ticks_per_rev", s.wheels.ticks_per_rev, 1, 1 << 24);
    wheels->read("counter_bits", s.wheels.counter_bits, 0, 62);
    if (s.wheels.counter_bits == 1)
      throw InputError(wheels->location("counter_bits"), "expected 0 (no wrap) or 2..62");
    wheels->read("start_phase", s.wheels.start_phase, -1.0, 0.999999);
    wheels->read("rate_bias_rl_radps", s.wheels.rate_bias_rl_radps, -10.0, 10.0);
    wheels->read("rate_bias_rr_radps", s.wheels.rate_bias_rr_radps, -10.0, 10.0);
    wheels->read("drive_force_sigma_n", s.wheels.drive_force_sigma_n, -1.0, 1e5);
    wheels->read("drive_force_scale", s.wheels.drive_force_scale, 0.1, 10.0);
    wheels->reject_unknown_keys();
  }
  sensors.reject_unknown_keys();
}

}  // namespace

std::vector<std::string> builtin_scenario_names() {
  std::vector<std::string> names;
  for (const auto& builtin : detail::builtin_scenarios()) names.emplace_back(builtin.name);
  return names;
}

sim::Scenario parse_scenario(const std::string& yaml_text, const std::string& file) {
  YamlMap root(detail::parse_yaml(yaml_text, file), file, "");
  sim::Scenario s;
  root.read("name", s.name);
  if (auto route = root.map("route")) parse_route(std::move(*route), s.route);
  if (s.route.segments.empty())
    throw InputError({file, 0, "route.segments"}, "a scenario needs at least one route segment");
  if (auto driver = root.map("driver")) {
    driver->read("max_speed_mps", s.driver.max_speed_mps, 0.1, 150.0);
    driver->read("max_reverse_speed_mps", s.driver.max_reverse_speed_mps, 0.1, 20.0);
    driver->read("max_lateral_acc_mps2", s.driver.max_lateral_acc_mps2, 0.1, 30.0);
    driver->read("max_acc_mps2", s.driver.max_acc_mps2, 0.1, 30.0);
    driver->read("max_brake_mps2", s.driver.max_brake_mps2, 0.1, 30.0);
    driver->read("friction_ellipse", s.driver.friction_ellipse);
    driver->read("max_power_wpkg", s.driver.max_power_wpkg, 0.0, 1e4);
    driver->read("start_dwell_s", s.driver.start_dwell_s, 0.0, 3600.0);
    driver->read("speed_variation", s.speed_variation, 0.0, 0.5);
    driver->reject_unknown_keys();
  }
  if (auto vehicle = root.map("vehicle")) {
    vehicle->read("track_width_m", s.vehicle.track_width_m, 0.1, 10.0);
    vehicle->read("effective_track_width_m", s.vehicle.effective_track_width_m, 0.0, 30.0);
    if (s.vehicle.effective_track_width_m > 0.0 && s.vehicle.effective_track_width_m < 0.1) {
      throw InputError(vehicle->location("effective_track_width_m"),
                       "expected 0 (the geometric track) or 0.1 to 30 m");
    }
    vehicle->read("wheelbase_m", s.vehicle.wheelbase_m, 0.1, 20.0);
    vehicle->read("tyre_radius_m", s.vehicle.tyre_radius_m, 0.05, 2.0);
    vehicle->read("wear_rl_mm", s.vehicle.wear_rl_mm, -50.0, 50.0);
    vehicle->read("wear_rr_mm", s.vehicle.wear_rr_mm, -50.0, 50.0);
    vehicle->read("pressure_rl", s.vehicle.pressure_rl, kTyrePressure.min, kTyrePressure.max);
    vehicle->read("pressure_rr", s.vehicle.pressure_rr, kTyrePressure.min, kTyrePressure.max);
    vehicle->read("ideal", s.ideal);
    if (auto dynamics = vehicle->map("dynamics")) {
      sim::VehicleDynamicsConfig& d = s.dynamics;
      dynamics->read("dynamic_lateral", d.dynamic_lateral);
      dynamics->read("longitudinal_slip", d.longitudinal_slip);
      dynamics->read("load_dependent_radius", d.load_dependent_radius);
      dynamics->read("load_transfer", d.load_transfer);
      dynamics->read("mass_kg", d.mass_kg, 100.0, 1e5);
      dynamics->read("yaw_inertia_kgm2", d.yaw_inertia_kgm2, 10.0, 1e6);
      dynamics->read("cg_to_front_axle_m", d.cg_to_front_axle_m, 0.1, s.vehicle.wheelbase_m - 0.1);
      dynamics->read("cg_height_m", d.cg_height_m, 0.0, 5.0);
      dynamics->read("front_roll_share", d.front_roll_share, 0.0, 1.0);
      dynamics->read("friction", d.friction, 0.1, 3.0);
      dynamics->read("cornering_stiffness_per_load_front", d.cornering_stiffness_per_load_front,
                     1.0, 100.0);
      dynamics->read("cornering_stiffness_per_load_rear", d.cornering_stiffness_per_load_rear, 1.0,
                     100.0);
      dynamics->read("lateral_shape", d.lateral_shape, 1.0, 2.0);
      dynamics->read("slip_stiffness_per_load", d.slip_stiffness_per_load, 1.0, 100.0);
      dynamics->read("longitudinal_shape", d.longitudinal_shape, 1.0, 2.0);
      dynamics->read("drag_area_m2", d.drag_area_m2, 0.0, 20.0);
      dynamics->read("air_density_kgpm3", d.air_density_kgpm3, 0.0, 2.0);
      dynamics->read("rolling_resistance", d.rolling_resistance, 0.0, 0.1);
      dynamics->read("brake_front_share", d.brake_front_share, 0.0, 1.0);
      if (dynamics->has("drivetrain")) {
        std::string drivetrain;
        dynamics->read("drivetrain", drivetrain);
        const auto parsed = parse_enum<Drivetrain>(drivetrain);
        if (!parsed) {
          throw InputError(dynamics->location("drivetrain"),
                           "expected " + enum_expected<Drivetrain>());
        }
        d.drivetrain = *parsed;
      }
      dynamics->read("drive_front_share_all", d.drive_front_share_all, 0.0, 1.0);
      dynamics->read("radius_load_sensitivity_m_per_n", d.radius_load_sensitivity_m_per_n, 0.0,
                     1e-4);
      dynamics->read("radius_speed_growth_s2pm2", d.radius_speed_growth_s2pm2, 0.0, 1e-4);
      dynamics->read("max_steer_rad", d.max_steer_rad, 0.05, 1.2);
      dynamics->read("preview_distance_m", d.preview_distance_m, 0.5, 100.0);
      dynamics->read("speed_gain_1ps", d.speed_gain_1ps, 0.0, 100.0);
      dynamics->read("position_gain_1ps2", d.position_gain_1ps2, 0.0, 100.0);
      dynamics->read("kinematic_below_mps", d.kinematic_below_mps, 0.5, 20.0);
      dynamics->read("step_hz", d.step_hz, 1000.0, 1e5);
      dynamics->read("control_hz", d.control_hz, 1.0, 1e4);
      dynamics->read("actuator_time_constant_s", d.actuator_time_constant_s, 0.0, 2.0);
      dynamics->reject_unknown_keys();
    }
    vehicle->reject_unknown_keys();
  }
  if (auto sensors = root.map("sensors")) parse_sensors(std::move(*sensors), s);
  if (auto seeds = root.map("seeds")) {
    seeds->read("trajectory", s.seeds.trajectory);
    seeds->read("noise", s.seeds.noise);
    seeds->reject_unknown_keys();
  }
  root.reject_unknown_keys();
  return s;
}

double use_track_file(sim::Scenario& scenario, const std::filesystem::path& track_csv) {
  const sim::CentrelineRoute route =
      sim::closed_route_from_centreline(read_track_centreline(track_csv));
  scenario.route.segments.clear();
  for (const sim::PathSegment& segment : route.segments)
    scenario.route.segments.push_back({segment, 0.0});
  scenario.route.repeat = 1;
  scenario.route.start = route.start;
  return route.max_deviation_m;
}

sim::Scenario load_scenario(const std::string& name_or_file) {
  for (const auto& builtin : detail::builtin_scenarios()) {
    if (name_or_file == builtin.name)
      return parse_scenario(std::string(builtin.yaml), "builtin:" + name_or_file);
  }
  std::ifstream stream(name_or_file);
  if (!stream) {
    throw InputError({name_or_file, 0, ""},
                     fmt::format("no such scenario file (built-in scenarios: {})",
                                 fmt::join(builtin_scenario_names(), ", ")));
  }
  std::ostringstream text;
  text << stream.rdbuf();
  return parse_scenario(text.str(), name_or_file);
}

std::string scenario_to_yaml(const sim::Scenario& s) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);  // exact round trip: the effective file reproduces the run
  const auto key = [&](const char* name, const auto& value) {
    out << YAML::Key << name << YAML::Value << value;
  };
  out << YAML::BeginMap;
  key("name", s.name);
  out << YAML::Key << "route" << YAML::Value << YAML::BeginMap;
  key("repeat", s.route.repeat);
  key("laps", s.route.laps);
  out << YAML::Key << "terrain" << YAML::Value << YAML::BeginMap;
  key("max_grade", s.route.terrain.max_grade);
  key("wavelength_m", s.route.terrain.wavelength_m);
  out << YAML::EndMap;
  out << YAML::Key << "start" << YAML::Value << YAML::Flow << YAML::BeginMap;
  key("x_m", s.route.start.x());
  key("y_m", s.route.start.y());
  key("heading_deg", deg_from_rad(s.route.start.z()));
  out << YAML::EndMap;
  out << YAML::Key << "segments" << YAML::Value << YAML::BeginSeq;
  for (const sim::RouteSegment& segment : s.route.segments) {
    out << YAML::Flow << YAML::BeginMap << YAML::Key << "clothoid" << YAML::Value << YAML::BeginMap;
    key("length_m", segment.geometry.length_m);
    key("curvature_start_1pm", segment.geometry.curvature_start_1pm);
    key("curvature_end_1pm", segment.geometry.curvature_end_1pm);
    out << YAML::EndMap;
    if (segment.geometry.direction < 0) key("reverse", true);
    if (segment.stop_dwell_s > 0) key("stop_s", segment.stop_dwell_s);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap;
  out << YAML::Key << "driver" << YAML::Value << YAML::BeginMap;
  key("max_speed_mps", s.driver.max_speed_mps);
  key("max_reverse_speed_mps", s.driver.max_reverse_speed_mps);
  key("max_lateral_acc_mps2", s.driver.max_lateral_acc_mps2);
  key("max_acc_mps2", s.driver.max_acc_mps2);
  key("max_brake_mps2", s.driver.max_brake_mps2);
  key("friction_ellipse", s.driver.friction_ellipse);
  key("max_power_wpkg", s.driver.max_power_wpkg);
  key("start_dwell_s", s.driver.start_dwell_s);
  key("speed_variation", s.speed_variation);
  out << YAML::EndMap;
  out << YAML::Key << "vehicle" << YAML::Value << YAML::BeginMap;
  key("track_width_m", s.vehicle.track_width_m);
  key("effective_track_width_m", s.vehicle.effective_track_width_m);
  key("wheelbase_m", s.vehicle.wheelbase_m);
  key("tyre_radius_m", s.vehicle.tyre_radius_m);
  key("wear_rl_mm", s.vehicle.wear_rl_mm);
  key("wear_rr_mm", s.vehicle.wear_rr_mm);
  key("pressure_rl", s.vehicle.pressure_rl);
  key("pressure_rr", s.vehicle.pressure_rr);
  key("ideal", s.ideal);
  const sim::VehicleDynamicsConfig& d = s.dynamics;
  out << YAML::Key << "dynamics" << YAML::Value << YAML::BeginMap;
  key("dynamic_lateral", d.dynamic_lateral);
  key("longitudinal_slip", d.longitudinal_slip);
  key("load_dependent_radius", d.load_dependent_radius);
  key("load_transfer", d.load_transfer);
  key("mass_kg", d.mass_kg);
  key("yaw_inertia_kgm2", d.yaw_inertia_kgm2);
  key("cg_to_front_axle_m", d.cg_to_front_axle_m);
  key("cg_height_m", d.cg_height_m);
  key("front_roll_share", d.front_roll_share);
  key("friction", d.friction);
  key("cornering_stiffness_per_load_front", d.cornering_stiffness_per_load_front);
  key("cornering_stiffness_per_load_rear", d.cornering_stiffness_per_load_rear);
  key("lateral_shape", d.lateral_shape);
  key("slip_stiffness_per_load", d.slip_stiffness_per_load);
  key("longitudinal_shape", d.longitudinal_shape);
  key("drag_area_m2", d.drag_area_m2);
  key("air_density_kgpm3", d.air_density_kgpm3);
  key("rolling_resistance", d.rolling_resistance);
  key("brake_front_share", d.brake_front_share);
  key("drivetrain", enum_name(d.drivetrain));
  key("drive_front_share_all", d.drive_front_share_all);
  key("radius_load_sensitivity_m_per_n", d.radius_load_sensitivity_m_per_n);
  key("radius_speed_growth_s2pm2", d.radius_speed_growth_s2pm2);
  key("max_steer_rad", d.max_steer_rad);
  key("preview_distance_m", d.preview_distance_m);
  key("speed_gain_1ps", d.speed_gain_1ps);
  key("position_gain_1ps2", d.position_gain_1ps2);
  key("kinematic_below_mps", d.kinematic_below_mps);
  key("step_hz", d.step_hz);
  key("control_hz", d.control_hz);
  key("actuator_time_constant_s", d.actuator_time_constant_s);
  out << YAML::EndMap << YAML::EndMap;
  out << YAML::Key << "sensors" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "gnss" << YAML::Value << YAML::BeginMap;
  key("rate_hz", s.gnss.rate_hz);
  key("sigma_m", s.gnss.sigma_m);
  key("gauss_markov_sigma_m", s.gnss.gauss_markov_sigma_m);
  key("gauss_markov_tau_s", s.gnss.gauss_markov_tau_s);
  key("outlier_rate", s.gnss.outlier_rate);
  key("outlier_min_m", s.gnss.outlier_min_m);
  key("outlier_max_m", s.gnss.outlier_max_m);
  key("latency_s", s.gnss.latency_s);
  key("lever_arm_x_m", s.gnss.lever_arm_x_m);
  key("lever_arm_y_m", s.gnss.lever_arm_y_m);
  key("lever_arm_stated", s.gnss.lever_arm_stated);
  key("altitude_sigma_m", s.gnss.altitude_sigma_m);
  key("speed_sigma_mps", s.gnss.speed_sigma_mps);
  out << YAML::Key << "outages" << YAML::Value << YAML::BeginSeq;
  for (const sim::Outage& outage : s.gnss.outages) {
    out << YAML::Flow << YAML::BeginMap;
    key("start_s", outage.start_s);
    key("duration_s", outage.duration_s);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
  key("output", s.gnss.output_latlon ? "latlon" : "local");
  key("altitude", altitude_name(s.gnss.altitude));
  out << YAML::Key << "origin" << YAML::Value << YAML::Flow << YAML::BeginMap;
  key("lat_deg", s.gnss.origin.latitude_deg);
  key("lon_deg", s.gnss.origin.longitude_deg);
  key("alt_m", s.gnss.origin.altitude_m);
  out << YAML::EndMap << YAML::EndMap;
  out << YAML::Key << "imu" << YAML::Value << YAML::BeginMap;
  key("rate_hz", s.imu.rate_hz);
  key("acc_sigma_mps2", s.imu.acc_sigma_mps2);
  key("yaw_rate_sigma_radps", s.imu.yaw_rate_sigma_radps);
  key("gyro_bias_radps", s.imu.gyro_bias_radps);
  key("mount_x_m", s.imu.mount_x_m);
  key("mount_y_m", s.imu.mount_y_m);
  out << YAML::EndMap;
  out << YAML::Key << "heading" << YAML::Value << YAML::BeginMap;
  key("rate_hz", s.heading.rate_hz);
  key("sigma_rad", s.heading.sigma_rad);
  key("bias_rad", s.heading.bias_rad);
  out << YAML::EndMap;
  out << YAML::Key << "wheels" << YAML::Value << YAML::BeginMap;
  key("rate_hz", s.wheels.rate_hz);
  key("output", enum_name(s.wheels.output));
  key("ticks_per_rev", s.wheels.ticks_per_rev);
  key("counter_bits", s.wheels.counter_bits);
  key("start_phase", s.wheels.start_phase);
  key("rate_bias_rl_radps", s.wheels.rate_bias_rl_radps);
  key("rate_bias_rr_radps", s.wheels.rate_bias_rr_radps);
  key("drive_force_sigma_n", s.wheels.drive_force_sigma_n);
  key("drive_force_scale", s.wheels.drive_force_scale);
  out << YAML::EndMap << YAML::EndMap;
  out << YAML::Key << "seeds" << YAML::Value << YAML::BeginMap;
  key("trajectory", s.seeds.trajectory);
  key("noise", s.seeds.noise);
  out << YAML::EndMap << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace odocal
