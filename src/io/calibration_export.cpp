#include "odocal/io/calibration_export.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "odocal/error.hpp"
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
  std::ifstream in(json_path);
  if (!in) throw InputError({json_path.string(), 0, ""}, "cannot open file");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError({json_path.string(), 0, ""}, std::string("not valid JSON: ") + e.what());
  }
  if (json.contains("usable") && json["usable"] == false) {
    throw InputError({json_path.string(), 0, "usable"},
                     "this calibration is not usable: " + json.value("message", std::string()));
  }
  const auto positive = [&](const char* key) {
    if (!json.contains(key) || !json[key].is_number() || !(json[key].get<double>() > 0.0) ||
        !std::isfinite(json[key].get<double>())) {
      throw InputError({json_path.string(), 0, key}, "expected a positive number");
    }
    return json[key].get<double>();
  };
  return {positive("circumference_rl_m"), positive("circumference_rr_m"),
          positive("track_width_m")};
}

}  // namespace odocal
