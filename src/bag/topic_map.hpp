#pragma once
// The topic map of `odocal import bag`, parsed and checked (every key named in errors).

#include <Eigen/Core>
#include <filesystem>
#include <optional>
#include <string>

#include "odocal/data/log.hpp"
#include "odocal/error.hpp"

namespace odocal::bag {

enum class StampSource { kHeader, kRecord };

struct TopicSource {
  std::string topic;
  StampSource stamp{StampSource::kHeader};
  double offset_s{};
  InputLocation where;  // the stream's section in the map, for errors
};

// A number in a message: its field path and the factor to SI units (unit, times `scale`).
struct FieldSource {
  std::string path;
  double to_si{1.0};
};

// The tyres' total longitudinal force from the car's bus (wheels.csv's drive_force_n): a number
// in any message (std_msgs/Float64, a vehicle interface's report), on its own topic.
struct DriveForceSource : TopicSource {
  FieldSource force;
};

struct WheelsSource : TopicSource {
  // sensor_msgs/JointState: the joints' positions (angle units) or velocities (angular speeds).
  std::string rl_joint, rr_joint;
  double rl_to_si{1.0}, rr_to_si{1.0};
  bool joint_velocity{};
  // Twist odometry (nav_msgs/Odometry, geometry_msgs/Twist*Stamped): forward speed and yaw
  // rate, empty paths for the message type's own (twist.twist.linear.x, ...).
  bool twist{};
  FieldSource speed, yaw_rate;
  std::optional<DriveForceSource> drive_force;  // interpolated onto the wheels' times
};

enum class GnssSigma { kCovariance, kNone, kFixed };

struct GnssSource : TopicSource {
  bool altitude{true};
  GnssSigma sigma{GnssSigma::kCovariance};
  double fixed_sigma_m{};
};

struct ImuSource : TopicSource {
  Eigen::Matrix3d body_R_sensor = Eigen::Matrix3d::Identity();
};

struct HeadingSource : TopicSource {
  Eigen::Matrix3d body_R_sensor = Eigen::Matrix3d::Identity();
  // A heading given as a number (a GNSS heading in std_msgs/Float64, ...): its field and unit;
  // empty path: the yaw of the message's orientation.
  FieldSource angle;
  bool compass_cw{};  // the orientation's yaw is clockwise from north (else ENU, as ROS's REP 103)
};

// tf's static transforms (tf2_msgs/TFMessage on /tf_static): where the sensors sit on the vehicle.
// `base` is the rear axle's centre, x forward, y left, z up (REP 103's base_link on a car); the
// IMU's frame gives its mounting and imu_x_m, imu_y_m, the antenna's gnss_x_m, gnss_y_m. An empty
// frame is not taken from tf.
struct FramesSource {
  std::string topic{"/tf_static"};
  std::string base{"base_link"};
  std::string imu, gnss;
  InputLocation where;  // the section in the map, for errors
};

struct TopicMap {
  std::string file;
  VehicleConfig vehicle;
  WheelsSource wheels;
  GnssSource gnss;
  std::optional<ImuSource> imu;
  std::optional<HeadingSource> heading;
  std::optional<FramesSource> frames;
  // Whether the map states the IMU's and the heading's mounting itself (else tf may).
  bool imu_mounting_stated{}, heading_mounting_stated{};
};

TopicMap read_topic_map(const std::filesystem::path& map_file);

}  // namespace odocal::bag
