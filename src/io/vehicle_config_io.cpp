#include "odocal/io/vehicle_config_io.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <string_view>

#include "odocal/error.hpp"

namespace odocal {
namespace {

constexpr std::array<std::string_view, 8> kKnownKeys = {
    "track_width_m", "circumference_rl_m", "circumference_rr_m", "ticks_per_rev",
    "counter_bits",  "wheelbase_m",        "circumference_fl_m", "circumference_fr_m"};

class VehicleYaml {
 public:
  explicit VehicleYaml(const std::filesystem::path& path) : file_(path.string()) {
    try {
      root_ = YAML::LoadFile(file_);
    } catch (const YAML::BadFile&) {
      throw InputError({file_, 0, ""}, "cannot open file");
    } catch (const YAML::Exception& e) {
      throw InputError({file_, static_cast<std::size_t>(e.mark.line + 1), ""},
                       "not valid YAML: " + e.msg);
    }
    if (!root_.IsMap()) throw InputError({file_, 1, ""}, "expected a mapping of key: value");
    for (const auto& entry : root_) {
      const std::string key = entry.first.as<std::string>();
      if (std::find(kKnownKeys.begin(), kKnownKeys.end(), key) == kKnownKeys.end()) {
        throw InputError(location(entry.first, key),
                         "unknown key (expected one of track_width_m, circumference_rl_m, "
                         "circumference_rr_m, ticks_per_rev, counter_bits, wheelbase_m, "
                         "circumference_fl_m, circumference_fr_m)");
      }
    }
  }

  double required_positive(const std::string& key) const {
    const auto value = optional_positive(key);
    if (!value) throw InputError({file_, 0, key}, "required key is missing");
    return *value;
  }

  std::optional<double> optional_positive(const std::string& key) const {
    const YAML::Node node = root_[key];
    if (!node) return std::nullopt;
    double value = 0.0;
    try {
      value = node.as<double>();
    } catch (const YAML::Exception&) {
      throw InputError(location(node, key), "expected a number, got '" + scalar(node) + "'");
    }
    if (!std::isfinite(value) || value <= 0.0) {
      throw InputError(location(node, key),
                       "expected a finite positive number, got '" + scalar(node) + "'");
    }
    return value;
  }

  std::optional<int> optional_integer(const std::string& key, int min, int max) const {
    const auto value = optional_positive(key);
    if (!value) return std::nullopt;
    if (*value != std::round(*value) || *value < min || *value > max) {
      throw InputError(
          location(root_[key], key),
          "expected an integer from " + std::to_string(min) + " to " + std::to_string(max));
    }
    return static_cast<int>(*value);
  }

  InputLocation location(const YAML::Node& node, const std::string& key) const {
    return {file_, static_cast<std::size_t>(node.Mark().line + 1), key};
  }

 private:
  static std::string scalar(const YAML::Node& node) {
    return node.IsScalar() ? node.Scalar() : std::string("<not a scalar>");
  }

  std::string file_;
  YAML::Node root_;
};

}  // namespace

VehicleConfig read_vehicle_config(const std::filesystem::path& path) {
  const VehicleYaml yaml(path);
  VehicleConfig vehicle;
  vehicle.track_width_m = yaml.required_positive("track_width_m");
  vehicle.circumference_rl_m = yaml.required_positive("circumference_rl_m");
  vehicle.circumference_rr_m = yaml.required_positive("circumference_rr_m");
  const auto ticks = yaml.optional_integer("ticks_per_rev", 1, 1 << 24);
  if (ticks) vehicle.ticks_per_rev = *ticks;
  vehicle.counter_bits = yaml.optional_integer("counter_bits", 2, 62);
  vehicle.wheelbase_m = yaml.optional_positive("wheelbase_m");
  vehicle.circumference_fl_m = yaml.optional_positive("circumference_fl_m");
  vehicle.circumference_fr_m = yaml.optional_positive("circumference_fr_m");
  return vehicle;
}

void write_vehicle_config(const VehicleConfig& vehicle, const std::filesystem::path& path) {
  YAML::Emitter out;
  out.SetDoublePrecision(12);
  out << YAML::BeginMap;
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
  out << YAML::EndMap;
  std::ofstream stream(path);
  stream << out.c_str() << "\n";
  if (!stream) throw Error("cannot write " + path.string());
}

}  // namespace odocal
