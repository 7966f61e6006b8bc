// odocal's own copies of the message definitions it imports, for bags that carry none (rosbag2
// SQLite3 before Iron) or a broken one. Field lists as in the ROS 2 interfaces (common_interfaces,
// rcl_interfaces); ROS 1 differs only in Header (seq, and time as a primitive).

#include <array>
#include <utility>

#include "message_types.hpp"

namespace odocal::bag {
namespace {

using Entry = std::pair<std::string_view, std::string_view>;

constexpr std::array kShared = {
    Entry{"geometry_msgs/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"},
    Entry{"geometry_msgs/Point", "float64 x\nfloat64 y\nfloat64 z\n"},
    Entry{"geometry_msgs/Quaternion", "float64 x\nfloat64 y\nfloat64 z\nfloat64 w\n"},
    Entry{"geometry_msgs/Pose",
          "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n"},
    Entry{"geometry_msgs/PoseWithCovariance", "geometry_msgs/Pose pose\nfloat64[36] covariance\n"},
    Entry{"geometry_msgs/Twist", "geometry_msgs/Vector3 linear\ngeometry_msgs/Vector3 angular\n"},
    Entry{"geometry_msgs/TwistWithCovariance",
          "geometry_msgs/Twist twist\nfloat64[36] covariance\n"},
    Entry{"geometry_msgs/TwistStamped", "std_msgs/Header header\ngeometry_msgs/Twist twist\n"},
    Entry{"geometry_msgs/TwistWithCovarianceStamped",
          "std_msgs/Header header\ngeometry_msgs/TwistWithCovariance twist\n"},
    Entry{"geometry_msgs/Vector3Stamped", "std_msgs/Header header\ngeometry_msgs/Vector3 vector\n"},
    Entry{"geometry_msgs/QuaternionStamped",
          "std_msgs/Header header\ngeometry_msgs/Quaternion quaternion\n"},
    Entry{"geometry_msgs/Transform",
          "geometry_msgs/Vector3 translation\ngeometry_msgs/Quaternion rotation\n"},
    Entry{"geometry_msgs/TransformStamped",
          "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/Transform transform\n"},
    Entry{"tf2_msgs/TFMessage", "geometry_msgs/TransformStamped[] transforms\n"},
    Entry{"sensor_msgs/Imu",
          "std_msgs/Header header\ngeometry_msgs/Quaternion orientation\n"
          "float64[9] orientation_covariance\ngeometry_msgs/Vector3 angular_velocity\n"
          "float64[9] angular_velocity_covariance\ngeometry_msgs/Vector3 linear_acceleration\n"
          "float64[9] linear_acceleration_covariance\n"},
    Entry{"sensor_msgs/NavSatStatus", "int8 status\nuint16 service\n"},
    Entry{"sensor_msgs/NavSatFix",
          "std_msgs/Header header\nsensor_msgs/NavSatStatus status\nfloat64 latitude\n"
          "float64 longitude\nfloat64 altitude\nfloat64[9] position_covariance\n"
          "uint8 position_covariance_type\n"},
    Entry{"sensor_msgs/JointState",
          "std_msgs/Header header\nstring[] name\nfloat64[] position\nfloat64[] velocity\n"
          "float64[] effort\n"},
    Entry{"nav_msgs/Odometry",
          "std_msgs/Header header\nstring child_frame_id\n"
          "geometry_msgs/PoseWithCovariance pose\ngeometry_msgs/TwistWithCovariance twist\n"},
    Entry{"std_msgs/Float64", "float64 data\n"},
    Entry{"std_msgs/Float32", "float32 data\n"},
    Entry{"std_msgs/String", "string data\n"},
};

constexpr std::array kRos2Only = {
    Entry{"builtin_interfaces/Time", "int32 sec\nuint32 nanosec\n"},
    Entry{"builtin_interfaces/Duration", "int32 sec\nuint32 nanosec\n"},
    Entry{"std_msgs/Header", "builtin_interfaces/Time stamp\nstring frame_id\n"},
};

constexpr std::array kRos1Only = {
    Entry{"std_msgs/Header", "uint32 seq\ntime stamp\nstring frame_id\n"},
};

template <std::size_t N>
std::string_view find(const std::array<Entry, N>& table, std::string_view type) {
  for (const Entry& entry : table)
    if (entry.first == type) return entry.second;
  return {};
}

}  // namespace

std::string_view builtin_definition(std::string_view type, MessageEncoding encoding) {
  const std::string_view own =
      encoding == MessageEncoding::kCdr ? find(kRos2Only, type) : find(kRos1Only, type);
  return own.empty() ? find(kShared, type) : own;
}

}  // namespace odocal::bag
