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
                              const std::filesystem::path& path) {
  VehicleConfig vehicle = nominal;
  vehicle.circumference_rl_m = calibrated.circumference_rl_m;
  vehicle.circumference_rr_m = calibrated.circumference_rr_m;
  vehicle.track_width_m = calibrated.track_width_m;
  write_vehicle_config(vehicle, path);
}

void write_ros2_diff_drive_parameters(const VehicleConfig& nominal,
                                      const OdometryParams& calibrated,
                                      const std::filesystem::path& path) {
  const double radius_m =
      (nominal.circumference_rl_m + nominal.circumference_rr_m) / (4.0 * std::numbers::pi);
  const double nominal_circumference = 2.0 * std::numbers::pi * radius_m;
  write_text_file(path, [&](TextBuffer& out) {
    out.print(
        "# ROS 2 diff_drive_controller parameters from odocal's calibration: the nominal geometry\n"
        "# and the multipliers that give the calibrated rear wheels and track.\n"
        "diff_drive_controller:\n"
        "  ros__parameters:\n"
        "    wheel_separation: {:.6f}\n"
        "    wheel_radius: {:.6f}\n"
        "    wheel_separation_multiplier: {:.8f}\n"
        "    left_wheel_radius_multiplier: {:.8f}\n"
        "    right_wheel_radius_multiplier: {:.8f}\n",
        nominal.track_width_m, radius_m, calibrated.track_width_m / nominal.track_width_m,
        calibrated.circumference_rl_m / nominal_circumference,
        calibrated.circumference_rr_m / nominal_circumference);
  });
}

OdometryParams read_calibrated_parameters(const std::filesystem::path& json_path) {
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

}  // namespace odocal
