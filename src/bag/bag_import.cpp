#include "odocal/bag/bag_import.hpp"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <optional>

#include "odocal/bag/bag_reader.hpp"
#include "odocal/bag/message_decoder.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/io/log_directory_output.hpp"
#include "odocal/io/vehicle_config_io.hpp"
#include "odocal/model/angle.hpp"
#include "static_transforms.hpp"
#include "topic_errors.hpp"
#include "topic_map.hpp"

namespace odocal::bag {
namespace {

namespace fs = std::filesystem;

// One stream's rows as read: time and the stream's values, in message order.
struct Rows {
  std::vector<double> t_s;
  std::vector<std::vector<double>> values;  // one vector per column
  std::size_t skipped{};                    // messages without usable values
  std::string skipped_why;
};

using RowBuilder = std::function<void(const DecodedFields&, double t_s, Rows&)>;

// A stream fed by one topic: the fields it decodes and how a message becomes a row.
struct Collector {
  std::string stream;  // "wheels", "gnss", ...
  const TopicSource* source{};
  std::size_t columns{};
  // Set once the topic is met: its decoder (paths chosen by the message type) and row builder.
  std::optional<MessageDecoder> decoder;
  RowBuilder build;
  bool seen{};
  std::size_t messages{};
  Rows rows;
};

struct Plan {
  std::vector<std::string> paths;  // without the stamp, which is prepended for header stamps
  RowBuilder build;
};

[[noreturn]] void wrong_type(const TopicSource& source, const std::string& stream,
                             const std::string& type, const std::string& expected) {
  throw_topic_of_wrong_type(source.where, source.topic, type, stream, expected);
}

Plan wheels_plan(const WheelsSource& source, const std::string& type, double track_width_m) {
  if (!source.twist) {
    if (type != "sensor_msgs/JointState")
      wrong_type(source, "wheels with rl/rr joints", type, "sensor_msgs/JointState");
    return {{"name", source.joint_velocity ? "velocity" : "position"},
            [&source](const DecodedFields& f, double t, Rows& rows) {
              const auto& names = f.strings[1];
              const auto& values = f.numbers[2];
              const auto at = [&](const std::string& joint) -> std::optional<double> {
                const auto it = std::find(names.begin(), names.end(), joint);
                const auto i = static_cast<std::size_t>(it - names.begin());
                if (it == names.end() || i >= values.size()) return std::nullopt;
                return values[i];
              };
              const auto rl = at(source.rl_joint), rr = at(source.rr_joint);
              if (!rl || !rr) {
                ++rows.skipped;
                rows.skipped_why = "without both wheel joints";
                return;
              }
              rows.t_s.push_back(t);
              rows.values[0].push_back(*rl * source.rl_to_si);
              rows.values[1].push_back(*rr * source.rr_to_si);
            }};
  }
  std::string speed = source.speed.path, yaw_rate = source.yaw_rate.path;
  if (speed.empty() || yaw_rate.empty()) {
    std::string prefix;
    if (type == "nav_msgs/Odometry" || type == "geometry_msgs/TwistWithCovarianceStamped") {
      prefix = "twist.twist.";
    } else if (type == "geometry_msgs/TwistStamped") {
      prefix = "twist.";
    } else {
      wrong_type(source, "wheels (twist odometry)", type,
                 "nav_msgs/Odometry, geometry_msgs/TwistStamped or "
                 "TwistWithCovarianceStamped (or name speed and yaw_rate fields)");
    }
    if (speed.empty()) speed = prefix + "linear.x";
    if (yaw_rate.empty()) yaw_rate = prefix + "angular.z";
  }
  const double speed_to_si = source.speed.path.empty() ? 1.0 : source.speed.to_si;
  const double yaw_to_si = source.yaw_rate.path.empty() ? 1.0 : source.yaw_rate.to_si;
  // Speed and yaw rate as the speeds of two wheels the nominal track apart (the log's mps
  // columns): the calibration's circumference factors and track then carry the twist's scales.
  return {{speed, yaw_rate}, [=](const DecodedFields& f, double t, Rows& rows) {
            const double v = f.numbers[1][0] * speed_to_si;
            const double w = f.numbers[2][0] * yaw_to_si;
            rows.t_s.push_back(t);
            rows.values[0].push_back(v - w * track_width_m / 2);
            rows.values[1].push_back(v + w * track_width_m / 2);
          }};
}

Plan gnss_plan(const GnssSource& source, const std::string& type) {
  if (type != "sensor_msgs/NavSatFix") wrong_type(source, "gnss", type, "sensor_msgs/NavSatFix");
  return {{"latitude", "longitude", "altitude", "position_covariance", "position_covariance_type",
           "status.status"},
          [&source](const DecodedFields& f, double t, Rows& rows) {
            const double lat = f.numbers[1][0], lon = f.numbers[2][0];
            // REP 145: status -1 is no fix; NaN positions are what drivers publish without one.
            if (f.numbers[6][0] < 0 || !std::isfinite(lat) || !std::isfinite(lon)) {
              ++rows.skipped;
              rows.skipped_why = "without a fix (status -1 or NaN position)";
              return;
            }
            const auto& covariance = f.numbers[4];
            double sigma = NAN;
            if (source.sigma == GnssSigma::kFixed) {
              sigma = source.fixed_sigma_m;
            } else if (source.sigma == GnssSigma::kCovariance && f.numbers[5][0] > 0 &&
                       covariance.size() == 9 && covariance[0] > 0 && covariance[4] > 0) {
              sigma = std::sqrt((covariance[0] + covariance[4]) / 2);  // horizontal 1-sigma
            }
            rows.t_s.push_back(t);
            rows.values[0].push_back(lat);
            rows.values[1].push_back(lon);
            rows.values[2].push_back(f.numbers[3][0]);
            rows.values[3].push_back(sigma);
          }};
}

Plan imu_plan(const ImuSource& source, const std::string& type) {
  if (type != "sensor_msgs/Imu") wrong_type(source, "imu", type, "sensor_msgs/Imu");
  return {{"angular_velocity.x", "angular_velocity.y", "angular_velocity.z",
           "linear_acceleration.x", "linear_acceleration.y", "linear_acceleration.z"},
          [&source](const DecodedFields& f, double t, Rows& rows) {
            const Eigen::Vector3d w =
                source.body_R_sensor *
                Eigen::Vector3d(f.numbers[1][0], f.numbers[2][0], f.numbers[3][0]);
            const Eigen::Vector3d a =
                source.body_R_sensor *
                Eigen::Vector3d(f.numbers[4][0], f.numbers[5][0], f.numbers[6][0]);
            rows.t_s.push_back(t);
            rows.values[0].push_back(a.x());
            rows.values[1].push_back(a.y());
            rows.values[2].push_back(w.z());
          }};
}

Plan heading_plan(const HeadingSource& source, const std::string& type) {
  if (!source.angle.path.empty()) {
    // A number: the sensor's yaw, less the mounting's yaw (a dual-antenna baseline turned
    // against the body).
    const double mounting_yaw = std::atan2(source.body_R_sensor(1, 0), source.body_R_sensor(0, 0));
    return {{source.angle.path},
            [&source, mounting_yaw](const DecodedFields& f, double t, Rows& rows) {
              double yaw = f.numbers[1][0] * source.angle.to_si;
              if (source.compass_cw) yaw = std::numbers::pi / 2 - yaw;
              rows.t_s.push_back(t);
              rows.values[0].push_back(wrap_angle(yaw - mounting_yaw));
            }};
  }
  std::string prefix;
  if (type == "sensor_msgs/Imu") {
    prefix = "orientation.";
  } else if (type == "geometry_msgs/QuaternionStamped") {
    prefix = "quaternion.";
  } else if (type == "nav_msgs/Odometry") {
    prefix = "pose.pose.orientation.";
  } else {
    wrong_type(source, "heading", type,
               "the orientation of sensor_msgs/Imu, geometry_msgs/QuaternionStamped or "
               "nav_msgs/Odometry");
  }
  return {{prefix + "x", prefix + "y", prefix + "z", prefix + "w"},
          [&source](const DecodedFields& f, double t, Rows& rows) {
            const Eigen::Quaterniond q(f.numbers[4][0], f.numbers[1][0], f.numbers[2][0],
                                       f.numbers[3][0]);
            // An IMU without an orientation estimate publishes zeros (REP 145).
            if (!(std::abs(q.norm() - 1.0) < 0.01)) {
              ++rows.skipped;
              rows.skipped_why = "without a unit orientation quaternion";
              return;
            }
            const Eigen::Matrix3d world_R_body =
                q.normalized().toRotationMatrix() * source.body_R_sensor.transpose();
            double yaw = std::atan2(world_R_body(1, 0), world_R_body(0, 0));
            if (source.compass_cw) yaw = std::numbers::pi / 2 - yaw;
            rows.t_s.push_back(t);
            rows.values[0].push_back(wrap_angle(yaw));
          }};
}

// A number in any message, in newtons: a message whose value is not finite is left out.
Plan drive_force_plan(const DriveForceSource& source) {
  return {{source.force.path}, [&source](const DecodedFields& f, double t, Rows& rows) {
            const double force = f.numbers[1][0] * source.force.to_si;
            if (!std::isfinite(force)) {
              ++rows.skipped;
              rows.skipped_why = "with a force that is not finite";
              return;
            }
            rows.t_s.push_back(t);
            rows.values[0].push_back(force);
          }};
}

// The drive force at each wheel row, linear between its messages; the wheel rows outside the
// force's span are left out (as the CSV importer keeps the rows where every value exists).
struct ForceOnWheels {
  std::vector<double> force_n;  // per wheel row, NaN where left out
  std::vector<std::size_t> rows;
};

ForceOnWheels force_on_wheels(const Rows& wheels, const Rows& force) {
  ForceOnWheels out;
  out.force_n.assign(wheels.t_s.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 0; k < wheels.t_s.size(); ++k) {
    const std::optional<double> value =
        interpolate_linear(force.t_s, force.values[0], wheels.t_s[k]);
    if (!value) continue;
    out.force_n[k] = *value;
    out.rows.push_back(k);
  }
  return out;
}

class ImportVisitor : public BagVisitor {
 public:
  ImportVisitor(std::vector<Collector>& collectors, const TopicMap& map, std::string bag)
      : collectors_(collectors), map_(map), bag_(std::move(bag)) {}

  void topic(std::size_t index, const BagTopic& topic) override {
    names_.push_back(topic.name);
    for (std::size_t c = 0; c < collectors_.size(); ++c) {
      Collector& collector = collectors_[c];
      if (collector.source->topic != topic.name) continue;
      const std::string type = canonical_type_name(topic.type);
      Plan plan = plan_for(collector, type);
      // Builders find the stamp at index 0; with record times it is not decoded (a message
      // without a header, such as std_msgs/Float64, has none) and its slot stays empty.
      std::vector<std::string> paths;
      if (collector.source->stamp == StampSource::kHeader) paths.emplace_back("header.stamp");
      paths.insert(paths.end(), plan.paths.begin(), plan.paths.end());
      const MessageEncoding encoding = message_encoding_from_name(topic.encoding, bag_);
      collector.decoder.emplace(topic.type, topic.definition, topic.definition_format, encoding,
                                paths, fmt::format("{}: topic {}", bag_, topic.name));
      collector.build = std::move(plan.build);
      collector.seen = true;
      collector.rows.values.assign(collector.columns, {});
      by_topic_.emplace(index, c);
    }
  }

  void message(const BagMessage& message) override {
    const auto [first, last] = by_topic_.equal_range(message.topic);
    for (auto it = first; it != last; ++it) {
      Collector& collector = collectors_[it->second];
      ++collector.messages;
      try {
        collector.decoder->decode(message.data, fields_);
      } catch (const DecodeError& e) {
        throw InputError({bag_, 0, collector.source->topic},
                         fmt::format("message {} (record time {:.6f} s): {}", collector.messages,
                                     static_cast<double>(message.record_time_ns) * 1e-9, e.what()));
      }
      const bool header = collector.source->stamp == StampSource::kHeader;
      if (!header) {
        fields_.numbers.insert(fields_.numbers.begin(), std::vector<double>{});
        fields_.strings.insert(fields_.strings.begin(), std::vector<std::string>{});
      }
      const double t_s =
          (header ? fields_.numbers[0][0] : static_cast<double>(message.record_time_ns) * 1e-9) +
          collector.source->offset_s;
      collector.build(fields_, t_s, collector.rows);
    }
  }

  // The topics met, for a message about one that is not there.
  std::string topic_names() const {
    std::string out;
    for (const std::string& name : names_) out += (out.empty() ? "" : ", ") + name;
    return out;
  }

 private:
  Plan plan_for(const Collector& collector, const std::string& type) const {
    if (collector.stream == "wheels")
      return wheels_plan(map_.wheels, type, map_.vehicle.track_width_m);
    if (collector.stream == "gnss") return gnss_plan(map_.gnss, type);
    if (collector.stream == "imu") return imu_plan(*map_.imu, type);
    if (collector.stream == "drive_force") return drive_force_plan(*map_.wheels.drive_force);
    return heading_plan(*map_.heading, type);
  }

  std::vector<Collector>& collectors_;
  const TopicMap& map_;
  std::string bag_;
  std::multimap<std::size_t, std::size_t> by_topic_;
  std::vector<std::string> names_;
  DecodedFields fields_;
};

// Sorts a stream's rows by time and drops rows whose time repeats (a bag is in record order,
// stamps need not be); returns how many were dropped.
std::size_t sort_rows(Rows& rows) {
  std::vector<std::size_t> order(rows.t_s.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return rows.t_s[a] < rows.t_s[b]; });
  std::vector<std::size_t> keep;
  for (std::size_t k : order) {
    if (!keep.empty() && !(rows.t_s[k] > rows.t_s[keep.back()])) continue;
    keep.push_back(k);
  }
  const std::size_t dropped = order.size() - keep.size();
  const auto pick = [&](const std::vector<double>& column) {
    std::vector<double> out(keep.size());
    for (std::size_t i = 0; i < keep.size(); ++i) out[i] = column[keep[i]];
    return out;
  };
  rows.t_s = pick(rows.t_s);
  for (auto& column : rows.values) column = pick(column);
  return dropped;
}

std::vector<std::size_t> all_rows(std::size_t n) {
  std::vector<std::size_t> rows(n);
  for (std::size_t k = 0; k < n; ++k) rows[k] = k;
  return rows;
}

bool all_finite(const std::vector<double>& column) {
  return std::all_of(column.begin(), column.end(), [](double v) { return std::isfinite(v); });
}

}  // namespace

ImportSummary import_bag(const fs::path& map_file, const fs::path& bag_path,
                         const fs::path& out_dir) {
  const TopicMap stated = read_topic_map(map_file);
  // tf's static transforms first, in a pass of their own: the IMU's mounting turns its messages.
  const TopicMap map = stated.frames ? with_static_transforms(
                                           stated, read_static_transforms(bag_path, *stated.frames))
                                     : stated;
  std::error_code error;
  if (fs::is_directory(bag_path, error)) refuse_overlapping_directories(bag_path, out_dir);

  std::vector<Collector> collectors;
  collectors.push_back({"wheels", &map.wheels, 2, {}, {}, false, 0, {}});
  collectors.push_back({"gnss", &map.gnss, 4, {}, {}, false, 0, {}});
  if (map.imu) collectors.push_back({"imu", &*map.imu, 3, {}, {}, false, 0, {}});
  if (map.heading) collectors.push_back({"heading", &*map.heading, 1, {}, {}, false, 0, {}});
  if (map.wheels.drive_force)
    collectors.push_back({"drive_force", &*map.wheels.drive_force, 1, {}, {}, false, 0, {}});

  ImportVisitor visitor(collectors, map, bag_path.string());
  read_bag(bag_path, visitor);

  ImportSummary notes_only;
  for (Collector& collector : collectors) {
    if (!collector.seen) {
      throw_topic_not_in_bag(collector.source->where, collector.source->topic,
                             visitor.topic_names());
    }
    if (collector.rows.skipped > 0) {
      notes_only.notes.push_back(fmt::format("{}: {} of {} messages {} left out", collector.stream,
                                             collector.rows.skipped, collector.messages,
                                             collector.rows.skipped_why));
    }
    if (const std::size_t dropped = sort_rows(collector.rows); dropped > 0) {
      notes_only.notes.push_back(
          fmt::format("{}: {} messages with a repeated time left out", collector.stream, dropped));
    }
    if (collector.rows.t_s.size() < 2) {
      throw InputError(
          collector.source->where,
          fmt::format("topic {} gives {} usable message(s) for {}; at least 2 needed",
                      collector.source->topic, collector.rows.t_s.size(), collector.stream));
    }
  }

  const auto rows_of = [&](const char* stream) -> const Rows* {
    for (const Collector& c : collectors)
      if (c.stream == stream) return &c.rows;
    return nullptr;
  };
  std::optional<ForceOnWheels> force;
  if (const Rows* force_rows = rows_of("drive_force")) {
    const Rows& wheels = *rows_of("wheels");
    force = force_on_wheels(wheels, *force_rows);
    if (force->rows.size() < 2) {
      throw InputError(map.wheels.drive_force->where,
                       fmt::format("topic {}'s messages ({:.3f} to {:.3f} s) do not span the "
                                   "wheels' ({:.3f} to {:.3f} s): another clock (time, offset_s)?",
                                   map.wheels.drive_force->topic, force_rows->t_s.front(),
                                   force_rows->t_s.back(), wheels.t_s.front(), wheels.t_s.back()));
    }
    if (const std::size_t outside = rows_of("wheels")->t_s.size() - force->rows.size()) {
      notes_only.notes.push_back(
          fmt::format("wheels: {} rows outside the drive force's messages left out", outside));
    }
  }

  LogDirectoryOutput output(out_dir);
  const fs::path& dir = output.staging();
  write_vehicle_config(map.vehicle, dir / "vehicle.yaml");
  for (Collector& collector : collectors) {
    Rows& rows = collector.rows;
    const auto every = all_rows(rows.t_s.size());
    std::vector<const std::vector<double>*> columns;
    for (const auto& column : rows.values) columns.push_back(&column);
    if (collector.stream == "drive_force") continue;  // a column of wheels.csv
    if (collector.stream == "wheels") {
      const char* unit = map.wheels.twist ? "mps" : map.wheels.joint_velocity ? "radps" : "rad";
      std::string header = fmt::format("t,rl_{0},rr_{0}", unit);
      std::vector<int> decimals = {9, 9};
      if (force) {
        header += ",drive_force_n";
        columns.push_back(&force->force_n);
        decimals.push_back(3);
      }
      write_stream_csv(dir / "wheels.csv", header, rows.t_s, columns, force ? force->rows : every,
                       decimals);
    } else if (collector.stream == "gnss") {
      std::string header = "t,lat,lon";
      std::vector<const std::vector<double>*> kept = {columns[0], columns[1]};
      std::vector<int> decimals = {9, 9};
      if (map.gnss.altitude && all_finite(rows.values[2])) {
        header += ",alt";
        kept.push_back(columns[2]);
        decimals.push_back(3);
      } else if (map.gnss.altitude) {
        notes_only.notes.emplace_back("gnss: altitude left out (not finite on every fix)");
      }
      if (map.gnss.sigma != GnssSigma::kNone && all_finite(rows.values[3])) {
        header += ",sigma_m";
        kept.push_back(columns[3]);
        decimals.push_back(3);
      } else if (map.gnss.sigma != GnssSigma::kNone) {
        notes_only.notes.emplace_back(
            "gnss: no sigma_m column (not every fix has a position covariance)");
      }
      write_stream_csv(dir / "gnss.csv", header, rows.t_s, kept, every, decimals);
    } else if (collector.stream == "imu") {
      write_stream_csv(dir / "imu.csv", "t,ax,ay,wz", rows.t_s, columns, every, {6, 6, 7});
    } else {
      write_stream_csv(dir / "heading.csv", "t,heading", rows.t_s, columns, every, {7});
    }
  }
  ImportSummary summary = check_staged_import(dir, out_dir);
  output.commit();
  summary.notes = std::move(notes_only.notes);
  return summary;
}

}  // namespace odocal::bag
