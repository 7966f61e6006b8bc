#include "odocal/io/calibration_export.hpp"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "odocal/data/physical_limits.hpp"
#include "odocal/error.hpp"
#include "odocal/io/input_file.hpp"
#include "odocal/io/text_output.hpp"
#include "odocal/io/vehicle_config_io.hpp"

namespace odocal {

void write_calibrated_vehicle(const VehicleConfig& nominal, const OdometryParams& calibrated,
                              const std::filesystem::path& path, const TyreModel& tyre) {
  VehicleConfig vehicle = nominal;
  vehicle.tyre_model = tyre.plain() ? std::nullopt : std::optional<TyreModel>(tyre);
  vehicle.circumference_rl_m = calibrated.circumference_rl_m;
  vehicle.circumference_rr_m = calibrated.circumference_rr_m;
  vehicle.track_width_m = calibrated.track_width_m;
  write_vehicle_config(vehicle, path);
}

void write_ros2_diff_drive_parameters(const VehicleConfig& nominal,
                                      const OdometryParams& calibrated,
                                      const std::filesystem::path& path, const TyreModel& tyre,
                                      const std::optional<ReferenceCircumference>& rolling) {
  const double radius_m =
      (nominal.circumference_rl_m + nominal.circumference_rr_m) / (4.0 * std::numbers::pi);
  const double nominal_circumference = 2.0 * std::numbers::pi * radius_m;
  const bool constant = tyre.plain();
  const bool at_speed = !constant && rolling.has_value();
  const std::string what = at_speed ? fmt::format(
                                          "the circumferences rolling straight at a "
                                          "steady\n# {:g} m/s, slip and load included",
                                          rolling->speed_mps)
                                    : std::string("the circumferences at rest");
  const std::string note =
      constant ? ""
               : fmt::format(
                     "# The calibration's tyre model (vehicle.yaml tyre_model: a circumference "
                     "that follows speed,\n# acceleration, turns, load; the rear axle's side "
                     "slip) cannot be carried by diff_drive_controller,\n# whose radii are "
                     "constant and whose axle does not slip sideways: these are\n# {}.\n",
                     what);
  const double left = at_speed ? rolling->circumference_rl_m : calibrated.circumference_rl_m;
  const double right = at_speed ? rolling->circumference_rr_m : calibrated.circumference_rr_m;
  write_text_file(path, [&](TextBuffer& out) {
    out.print(
        "# ROS 2 diff_drive_controller parameters from odocal's calibration: the nominal geometry\n"
        "# and the multipliers that give the calibrated rear wheels and track.\n"
        "{}"
        "diff_drive_controller:\n"
        "  ros__parameters:\n"
        "    wheel_separation: {:.6f}\n"
        "    wheel_radius: {:.6f}\n"
        "    wheel_separation_multiplier: {:.8f}\n"
        "    left_wheel_radius_multiplier: {:.8f}\n"
        "    right_wheel_radius_multiplier: {:.8f}\n",
        note, nominal.track_width_m, radius_m, calibrated.track_width_m / nominal.track_width_m,
        left / nominal_circumference, right / nominal_circumference);
  });
}

namespace {

// The result JSON, checked to be an object of a usable calibration.
nlohmann::json calibration_json(const std::filesystem::path& json_path) {
  const std::string text = read_input_file(json_path);
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // syntax, or a number out of range (1e400)
    throw InputError({json_path.string(), 0, ""}, std::string("not valid JSON: ") + e.what());
  }
  if (!json.is_object())
    throw InputError({json_path.string(), 0, ""}, "expected a calibration result (JSON object)");
  if (json.contains("usable") && json["usable"] == false) {
    throw InputError({json_path.string(), 0, "usable"},
                     "this calibration is not usable: " + json.value("message", std::string()));
  }
  return json;
}

}  // namespace

OdometryParams read_calibrated_parameters(const std::filesystem::path& json_path) {
  const nlohmann::json json = calibration_json(json_path);
  const auto value = [&](const char* key, PhysicalRange range) {
    if (!json.contains(key) || !json[key].is_number() || !range.contains(json[key].get<double>())) {
      throw InputError({json_path.string(), 0, key},
                       fmt::format("expected a number from {} to {}", range.min, range.max));
    }
    return json[key].get<double>();
  };
  return {value("circumference_rl_m", kCircumferenceM),
          value("circumference_rr_m", kCircumferenceM), value("track_width_m", kTrackWidthM)};
}

TyreModel read_calibrated_tyre_model(const std::filesystem::path& json_path) {
  const nlohmann::json json = calibration_json(json_path);
  TyreModel model;
  if (!json.contains("parameters") || !json["parameters"].is_array()) return model;
  for (const nlohmann::json& p : json["parameters"]) {
    if (!p.is_object() || !p.contains("name") || !p["name"].is_string()) continue;
    if (!p.value("estimated", false)) continue;
    for (const TyreCoefficient& coefficient : kTyreCoefficients) {
      const std::string name = tyre_parameter_name(coefficient);
      if (p["name"] != name) continue;
      const PhysicalRange range{coefficient.min, coefficient.max};
      if (!p.contains("value") || !p["value"].is_number() ||
          !range.contains(p["value"].get<double>())) {
        throw InputError({json_path.string(), 0, "parameters." + name},
                         fmt::format("expected a number from {} to {}", range.min, range.max));
      }
      model.*(coefficient.member) = p["value"].get<double>();
    }
  }
  return model;
}

std::optional<Eigen::Vector2d> read_calibrated_antenna(const std::filesystem::path& json_path) {
  const nlohmann::json json = calibration_json(json_path);
  if (!json.contains("parameters") || !json["parameters"].is_array()) return std::nullopt;
  std::optional<double> place[2];
  for (const nlohmann::json& p : json["parameters"]) {
    if (!p.is_object() || !p.contains("name") || !p["name"].is_string()) continue;
    const std::string name = p["name"];
    const int axis = name == "lever_arm_x_m" ? 0 : name == "lever_arm_y_m" ? 1 : -1;
    if (axis < 0 || !p.value("estimated", false) || !p.value("identified", false)) continue;
    if (!p.contains("value") || !p["value"].is_number() ||
        !kMountingOffsetM.contains(p["value"].get<double>())) {
      throw InputError({json_path.string(), 0, "parameters." + name},
                       fmt::format("expected a number from {} to {}", kMountingOffsetM.min,
                                   kMountingOffsetM.max));
    }
    place[axis] = p["value"].get<double>();
  }
  if (!place[0] || !place[1]) return std::nullopt;
  return Eigen::Vector2d(*place[0], *place[1]);
}

}  // namespace odocal
