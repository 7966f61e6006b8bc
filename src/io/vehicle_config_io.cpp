#include "odocal/io/vehicle_config_io.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string_view>

#include "odocal/data/physical_limits.hpp"
#include "odocal/error.hpp"
#include "odocal/io/input_file.hpp"
#include "odocal/io/output_file.hpp"
#include "vehicle_config_parse.hpp"

namespace odocal {
namespace {

// vehicle.yaml's body: what the tyre model's physical terms need beyond wheelbase and track.
struct BodyField {
  const char* key;
  double VehicleBody::*member;
  PhysicalRange range;
};
constexpr std::array<BodyField, 13> kBodyFields{{
    {"rear_axle_load_share", &VehicleBody::rear_axle_load_share, kAxleLoadShare},
    {"cg_height_m", &VehicleBody::cg_height_m, kCgHeightM},
    {"rear_roll_share", &VehicleBody::rear_roll_share, kRollShare},
    {"mass_kg", &VehicleBody::mass_kg, kVehicleMassKg},
    {"drag_area_m2", &VehicleBody::drag_area_m2, kDragAreaM2},
    {"rolling_resistance", &VehicleBody::rolling_resistance, kRollingResistance},
    {"friction", &VehicleBody::friction, kTyreFriction},
    {"slip_curve_shape", &VehicleBody::slip_curve_shape, kSlipCurveShape},
    {"brake_rear_share", &VehicleBody::brake_rear_share, kAxleForceShare},
    {"all_wheel_drive_rear_share", &VehicleBody::all_wheel_drive_rear_share, kAxleForceShare},
    {"front_cornering_stiffness", &VehicleBody::front_cornering_stiffness,
     kCorneringStiffnessPerLoad},
    {"rear_cornering_stiffness", &VehicleBody::rear_cornering_stiffness,
     kCorneringStiffnessPerLoad},
    {"lateral_curve_shape", &VehicleBody::lateral_curve_shape, kSlipCurveShape},
}};

// A sensor's place forward and left of the rear axle's centre, where either key is given (the
// other then zero).
std::optional<Eigen::Vector2d> mounting_position(detail::YamlMap& map, const char* x_key,
                                                 const char* y_key) {
  if (!map.has(x_key) && !map.has(y_key)) return std::nullopt;
  Eigen::Vector2d place = Eigen::Vector2d::Zero();
  map.read(x_key, place.x(), kMountingOffsetM.min, kMountingOffsetM.max);
  map.read(y_key, place.y(), kMountingOffsetM.min, kMountingOffsetM.max);
  return place;
}

void write_mounting_position(YAML::Emitter& out, const std::optional<Eigen::Vector2d>& place,
                             const char* x_key, const char* y_key) {
  if (!place) return;
  out << YAML::Key << x_key << YAML::Value << place->x();
  out << YAML::Key << y_key << YAML::Value << place->y();
}

}  // namespace

namespace detail {

VehicleConfig parse_vehicle_config(YamlMap& map) {
  VehicleConfig vehicle;
  const auto required = [&](const std::string& key, double& value, PhysicalRange range) {
    if (!map.has(key))
      throw InputError({map.file(), 0, map.key_path(key)}, "required key is missing");
    map.read(key, value, range.min, range.max);
  };
  const auto optional = [&](const std::string& key, std::optional<double>& value,
                            PhysicalRange range) {
    if (!map.has(key)) return;
    double read = 0.0;
    map.read(key, read, range.min, range.max);
    value = read;
  };
  if (map.has("vehicle_id")) {
    std::string id;
    map.read("vehicle_id", id);
    const bool valid =
        !id.empty() && id.size() <= 64 && std::all_of(id.begin(), id.end(), [](unsigned char ch) {
          return std::isalnum(ch) || ch == '.' || ch == '_' || ch == '-';
        });
    if (!valid) {
      throw InputError(map.location("vehicle_id"),
                       "expected 1 to 64 letters, digits, '.', '_' or '-'");
    }
    vehicle.vehicle_id = id;
  }
  required("track_width_m", vehicle.track_width_m, kTrackWidthM);
  required("circumference_rl_m", vehicle.circumference_rl_m, kCircumferenceM);
  required("circumference_rr_m", vehicle.circumference_rr_m, kCircumferenceM);
  if (map.has("ticks_per_rev")) {
    int ticks = 0;
    map.read("ticks_per_rev", ticks, 1, 1 << 24);
    vehicle.ticks_per_rev = ticks;
  }
  if (map.has("counter_bits")) {
    int bits = 0;
    map.read("counter_bits", bits, 2, 62);
    vehicle.counter_bits = bits;
  }
  optional("wheelbase_m", vehicle.wheelbase_m, kWheelbaseM);
  optional("circumference_fl_m", vehicle.circumference_fl_m, kCircumferenceM);
  optional("circumference_fr_m", vehicle.circumference_fr_m, kCircumferenceM);
  vehicle.imu_position_m = mounting_position(map, "imu_x_m", "imu_y_m");
  vehicle.gnss_position_m = mounting_position(map, "gnss_x_m", "gnss_y_m");
  if (auto tyre = map.map("tyre_model")) {
    TyreModel model;
    for (const TyreCoefficient& coefficient : kTyreCoefficients)
      tyre->read(coefficient.key, model.*(coefficient.member), coefficient.min, coefficient.max);
    tyre->reject_unknown_keys();
    vehicle.tyre_model = model;
  }
  if (auto body = map.map("body")) {
    for (const BodyField& field : kBodyFields)
      body->read(field.key, vehicle.body.*(field.member), field.range.min, field.range.max);
    if (body->has("drivetrain")) {
      std::string drivetrain;
      body->read("drivetrain", drivetrain);
      vehicle.body.drivetrain = parse_enum<Drivetrain>(drivetrain);
      if (!vehicle.body.drivetrain) {
        throw InputError(body->location("drivetrain"),
                         "expected " + enum_expected<Drivetrain>() + ", not '" + drivetrain + "'");
      }
    }
    body->reject_unknown_keys();
  }
  map.reject_unknown_keys();
  return vehicle;
}

}  // namespace detail

VehicleConfig read_vehicle_config(const std::filesystem::path& path) {
  detail::YamlMap map(detail::parse_yaml(read_input_file(path), path.string()), path.string(), "");
  return detail::parse_vehicle_config(map);
}

void write_vehicle_config(const VehicleConfig& vehicle, const std::filesystem::path& path) {
  YAML::Emitter out;
  out.SetDoublePrecision(12);
  out << YAML::BeginMap;
  if (vehicle.vehicle_id) out << YAML::Key << "vehicle_id" << YAML::Value << *vehicle.vehicle_id;
  out << YAML::Key << "track_width_m" << YAML::Value << vehicle.track_width_m;
  out << YAML::Key << "circumference_rl_m" << YAML::Value << vehicle.circumference_rl_m;
  out << YAML::Key << "circumference_rr_m" << YAML::Value << vehicle.circumference_rr_m;
  if (vehicle.ticks_per_rev) {
    out << YAML::Key << "ticks_per_rev" << YAML::Value << static_cast<long>(*vehicle.ticks_per_rev);
  }
  if (vehicle.counter_bits)
    out << YAML::Key << "counter_bits" << YAML::Value << *vehicle.counter_bits;
  if (vehicle.wheelbase_m) out << YAML::Key << "wheelbase_m" << YAML::Value << *vehicle.wheelbase_m;
  if (vehicle.circumference_fl_m) {
    out << YAML::Key << "circumference_fl_m" << YAML::Value << *vehicle.circumference_fl_m;
  }
  if (vehicle.circumference_fr_m) {
    out << YAML::Key << "circumference_fr_m" << YAML::Value << *vehicle.circumference_fr_m;
  }
  write_mounting_position(out, vehicle.imu_position_m, "imu_x_m", "imu_y_m");
  write_mounting_position(out, vehicle.gnss_position_m, "gnss_x_m", "gnss_y_m");
  if (vehicle.tyre_model) {
    const TyreModel& m = *vehicle.tyre_model;
    out << YAML::Key << "tyre_model" << YAML::Value << YAML::BeginMap;
    for (const TyreCoefficient& coefficient : kTyreCoefficients) {
      if (m.*(coefficient.member) != 0.0)
        out << YAML::Key << coefficient.key << YAML::Value << m.*(coefficient.member);
    }
    out << YAML::EndMap;
  }
  const VehicleBody defaults;
  const bool stated_numbers =
      std::any_of(kBodyFields.begin(), kBodyFields.end(),
                  [&](const auto& f) { return vehicle.body.*(f.member) != defaults.*(f.member); });
  if (stated_numbers || vehicle.body.drivetrain) {
    out << YAML::Key << "body" << YAML::Value << YAML::BeginMap;
    if (vehicle.body.drivetrain)
      out << YAML::Key << "drivetrain" << YAML::Value << enum_name(*vehicle.body.drivetrain);
    for (const BodyField& field : kBodyFields) {
      if (stated_numbers)
        out << YAML::Key << field.key << YAML::Value << vehicle.body.*(field.member);
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
  write_output_file(path, std::string(out.c_str()) + "\n");
}

}  // namespace odocal
