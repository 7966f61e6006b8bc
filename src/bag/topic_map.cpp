#include "topic_map.hpp"

#include <Eigen/Geometry>
#include <numbers>

#include "odocal/io/input_file.hpp"
#include "units.hpp"
#include "vehicle_config_parse.hpp"
#include "yaml_map.hpp"

namespace odocal::bag {
namespace {

using detail::Quantity;
using detail::YamlMap;

StampSource stamp_source(YamlMap& map, const std::string& key, StampSource fallback) {
  if (!map.has(key)) return fallback;
  std::string text;
  map.read(key, text);
  if (text == "header") return StampSource::kHeader;
  if (text == "record") return StampSource::kRecord;
  throw InputError(map.location(key),
                   "expected header (the message's header.stamp) or record (the bag's receive "
                   "time)");
}

void read_topic(YamlMap& map, StampSource default_stamp, TopicSource& out) {
  out.where = map.location();
  if (!map.has("topic")) throw InputError(map.location(), "'topic' is missing");
  map.read("topic", out.topic);
  out.stamp = stamp_source(map, "time", default_stamp);
  map.read("offset_s", out.offset_s, -1e10, 1e10);
}

// A unit of one of `quantities`, times an optional `scale` (-1 for a flipped sign).
double unit_factor(YamlMap& map, std::initializer_list<Quantity> quantities,
                   Quantity* found = nullptr) {
  std::string name;
  map.read("unit", name);
  if (name.empty()) throw InputError(map.location(), "'unit' is missing");
  const auto unit = detail::parse_unit(name);
  if (!unit ||
      std::find(quantities.begin(), quantities.end(), unit->quantity) == quantities.end()) {
    std::string accepted;
    for (Quantity q : quantities)
      accepted += (accepted.empty() ? "" : ", ") + detail::unit_names(q);
    throw InputError(map.location("unit"), "expected one of " + accepted);
  }
  double scale = 1.0;
  map.read("scale", scale, -1e6, 1e6);
  if (scale == 0.0) throw InputError(map.location("scale"), "must not be 0");
  if (found) *found = unit->quantity;
  return unit->to_si * scale;
}

FieldSource field_source(YamlMap& parent, const std::string& key, Quantity quantity) {
  FieldSource out;
  auto map = parent.map(key);
  if (!map) return out;
  map->read("field", out.path);
  out.to_si = unit_factor(*map, {quantity});
  map->reject_unknown_keys();
  return out;
}

Eigen::Matrix3d mounting(YamlMap& parent) {
  auto map = parent.map("mounting");
  if (!map) return Eigen::Matrix3d::Identity();
  double yaw = 0, pitch = 0, roll = 0;
  map->read("yaw_deg", yaw, -360, 360);
  map->read("pitch_deg", pitch, -360, 360);
  map->read("roll_deg", roll, -360, 360);
  map->reject_unknown_keys();
  constexpr double kDeg = std::numbers::pi / 180.0;
  // tf's convention (static_transform_publisher yaw pitch roll): body_R_sensor = Rz Ry Rx.
  return (Eigen::AngleAxisd(yaw * kDeg, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch * kDeg, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll * kDeg, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

void read_drive_force(YamlMap& wheels, StampSource stamp, WheelsSource& out) {
  auto map = wheels.map("drive_force");
  if (!map) return;
  DriveForceSource& source = out.drive_force.emplace();
  read_topic(*map, stamp, source);
  map->read("field", source.force.path);
  if (source.force.path.empty()) throw InputError(map->location(), "'field' is missing");
  source.force.to_si = unit_factor(*map, {Quantity::kForce});
  map->reject_unknown_keys();
}

void read_wheels(YamlMap& map, StampSource stamp, WheelsSource& out) {
  read_topic(map, stamp, out);
  read_drive_force(map, stamp, out);
  const bool joints = map.has("rl") || map.has("rr");
  out.twist = !joints;
  if (out.twist) {
    out.speed = field_source(map, "speed", Quantity::kSpeed);
    out.yaw_rate = field_source(map, "yaw_rate", Quantity::kAngularSpeed);
    return;
  }
  bool velocity[2]{};
  for (const char* wheel : {"rl", "rr"}) {
    auto wheel_map = map.map(wheel);
    if (!wheel_map) throw InputError(map.location(), std::string("'") + wheel + "' is missing");
    const bool left = wheel[1] == 'l';
    std::string& joint = left ? out.rl_joint : out.rr_joint;
    wheel_map->read("joint", joint);
    if (joint.empty()) throw InputError(wheel_map->location(), "'joint' is missing");
    Quantity quantity{};
    (left ? out.rl_to_si : out.rr_to_si) =
        unit_factor(*wheel_map, {Quantity::kAngle, Quantity::kAngularSpeed}, &quantity);
    velocity[left ? 0 : 1] = quantity == Quantity::kAngularSpeed;
    wheel_map->reject_unknown_keys();
  }
  if (velocity[0] != velocity[1])
    throw InputError(map.location(), "rl and rr must both be positions or both velocities");
  out.joint_velocity = velocity[0];
}

void read_gnss(YamlMap& map, StampSource stamp, GnssSource& out) {
  read_topic(map, stamp, out);
  map.read("altitude", out.altitude);
  if (map.has("sigma")) {
    std::string text;
    try {
      map.read("sigma", text);
    } catch (const InputError&) {
      text.clear();
    }
    if (text == "covariance") {
      out.sigma = GnssSigma::kCovariance;
    } else if (text == "none") {
      out.sigma = GnssSigma::kNone;
    } else {
      out.sigma = GnssSigma::kFixed;
      map.read("sigma", out.fixed_sigma_m, 1e-4, 1e4);
    }
  }
}

// frames: the frames tf places the sensors by; a place stated also in the map is refused (two
// places for one sensor).
FramesSource read_frames(YamlMap& map, const TopicMap& topics) {
  FramesSource out;
  out.where = map.location();
  map.read("topic", out.topic);
  map.read("base", out.base);
  map.read("imu", out.imu);
  map.read("gnss", out.gnss);
  map.reject_unknown_keys();
  if (out.base.empty()) throw InputError(map.location("base"), "must name a frame");
  if (!out.imu.empty()) {
    if (!topics.imu)
      throw InputError(map.location("imu"), "there is no imu stream to place (streams.imu)");
    if (topics.imu_mounting_stated || topics.vehicle.imu_position_m) {
      throw InputError(map.location("imu"),
                       "the IMU is placed by tf and by the map (streams.imu.mounting or vehicle's "
                       "imu_x_m, imu_y_m): state it in one place");
    }
  }
  if (!out.gnss.empty() && topics.vehicle.gnss_position_m) {
    throw InputError(map.location("gnss"),
                     "the antenna is placed by tf and by vehicle's gnss_x_m, gnss_y_m: state it "
                     "in one place");
  }
  return out;
}

}  // namespace

TopicMap read_topic_map(const std::filesystem::path& map_file) {
  TopicMap out;
  out.file = map_file.string();
  const YAML::Node root_node = detail::parse_yaml(read_input_file(map_file), out.file);
  YamlMap root(root_node, out.file, "");
  auto vehicle = root.map("vehicle");
  if (!vehicle) throw InputError({out.file, 0, "vehicle"}, "required section is missing");
  out.vehicle = detail::parse_vehicle_config(*vehicle);
  const StampSource stamp = stamp_source(root, "time", StampSource::kHeader);
  auto streams = root.map("streams");
  if (!streams) throw InputError({out.file, 0, "streams"}, "required section is missing");
  auto wheels = streams->map("wheels");
  if (!wheels) throw InputError({out.file, 0, "streams.wheels"}, "required stream is missing");
  read_wheels(*wheels, stamp, out.wheels);
  wheels->reject_unknown_keys();
  auto gnss = streams->map("gnss");
  if (!gnss) throw InputError({out.file, 0, "streams.gnss"}, "required stream is missing");
  read_gnss(*gnss, stamp, out.gnss);
  gnss->reject_unknown_keys();
  if (auto imu = streams->map("imu")) {
    ImuSource& source = out.imu.emplace();
    read_topic(*imu, stamp, source);
    out.imu_mounting_stated = imu->has("mounting");
    source.body_R_sensor = mounting(*imu);
    imu->reject_unknown_keys();
  }
  if (auto heading = streams->map("heading")) {
    HeadingSource& source = out.heading.emplace();
    read_topic(*heading, stamp, source);
    out.heading_mounting_stated = heading->has("mounting");
    source.body_R_sensor = mounting(*heading);
    source.angle = field_source(*heading, "angle", Quantity::kAngle);
    if (auto angle = heading->map("angle"); angle && source.angle.path.empty())
      throw InputError(angle->location(), "'field' is missing");
    std::string convention = "enu_ccw";
    heading->read("convention", convention);
    if (convention != "enu_ccw" && convention != "compass_cw")
      throw InputError(heading->location("convention"), "expected enu_ccw or compass_cw");
    source.compass_cw = convention == "compass_cw";
    heading->reject_unknown_keys();
  }
  streams->reject_unknown_keys();
  if (auto frames = root.map("frames")) out.frames = read_frames(*frames, out);
  root.reject_unknown_keys();
  return out;
}

}  // namespace odocal::bag
