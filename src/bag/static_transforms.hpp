#pragma once
// tf's static transforms in a bag (tf2_msgs/TFMessage, docs/importing.md, "The sensors' places
// from tf"): read in a pass of their own, so that the sensors' mountings are known before their
// messages are turned into the vehicle's frame.

#include <Eigen/Geometry>
#include <filesystem>
#include <map>
#include <string>

#include "topic_map.hpp"

namespace odocal::bag {

// Every parent_T_child the topic gives (the last one of a child counts), by child frame; frame
// names without a leading '/' (ROS 1's tf_prefix).
struct StaticTransforms {
  struct Link {
    std::string parent;
    Eigen::Isometry3d parent_T_child = Eigen::Isometry3d::Identity();
  };
  std::map<std::string, Link> by_child;

  // base_T_frame through the tree; throws InputError at `where` when tf has no such frame or it
  // is not connected to base.
  Eigen::Isometry3d base_T(const std::string& base, const std::string& frame,
                           const InputLocation& where) const;
};

StaticTransforms read_static_transforms(const std::filesystem::path& bag_path,
                                        const FramesSource& frames);

// The map with tf's places taken in: the IMU's mounting (and the heading's, where it reads the
// IMU's topic and states none) and imu_x_m, imu_y_m; the antenna's gnss_x_m, gnss_y_m.
TopicMap with_static_transforms(TopicMap map, const StaticTransforms& transforms);

}  // namespace odocal::bag
