#include "static_transforms.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "odocal/bag/bag_reader.hpp"
#include "odocal/bag/message_decoder.hpp"
#include "odocal/error.hpp"
#include "topic_errors.hpp"

namespace odocal::bag {
namespace {

// A quaternion this far from unit length is not a rotation (a writer's zeros); closer, normalised.
constexpr double kUnitQuaternionTolerance = 1e-3;

std::string frame_name(std::string name) {
  while (!name.empty() && name.front() == '/') name.erase(name.begin());
  return name;
}

const std::vector<std::string> kPaths = {
    "transforms.header.frame_id",         "transforms.child_frame_id",
    "transforms.transform.translation.x", "transforms.transform.translation.y",
    "transforms.transform.translation.z", "transforms.transform.rotation.x",
    "transforms.transform.rotation.y",    "transforms.transform.rotation.z",
    "transforms.transform.rotation.w"};

class TransformVisitor : public BagVisitor {
 public:
  TransformVisitor(const FramesSource& frames, std::string bag)
      : frames_(frames), bag_(std::move(bag)) {}

  void topic(std::size_t index, const BagTopic& topic) override {
    names_ += (names_.empty() ? "" : ", ") + topic.name;
    if (topic.name != frames_.topic) return;
    const std::string type = canonical_type_name(topic.type);
    if (type != "tf2_msgs/TFMessage") {
      throw_topic_of_wrong_type(frames_.where, topic.name, type, "frames", "tf2_msgs/TFMessage");
    }
    decoder_.emplace(topic.type, topic.definition, topic.definition_format,
                     message_encoding_from_name(topic.encoding, bag_), kPaths,
                     fmt::format("{}: topic {}", bag_, topic.name));
    index_ = index;
  }

  void message(const BagMessage& message) override {
    if (!decoder_ || message.topic != index_) return;
    ++messages_;
    try {
      decoder_->decode(message.data, fields_);
    } catch (const DecodeError& e) {
      throw InputError({bag_, 0, frames_.topic},
                       fmt::format("message {}: {}", messages_, e.what()));
    }
    const std::size_t count = fields_.strings[1].size();
    for (std::size_t i = 0; i < count; ++i) {
      const auto number = [&](std::size_t path) { return fields_.numbers[path][i]; };
      const Eigen::Quaterniond q(number(8), number(5), number(6), number(7));
      const std::string child = frame_name(fields_.strings[1][i]);
      if (!(std::abs(q.norm() - 1.0) <= kUnitQuaternionTolerance)) {
        throw InputError({bag_, 0, frames_.topic},
                         fmt::format("message {}: the rotation to frame '{}' is not a unit "
                                     "quaternion (norm {:.6g})",
                                     messages_, child, q.norm()));
      }
      StaticTransforms::Link link;
      link.parent = frame_name(fields_.strings[0][i]);
      link.parent_T_child.linear() = q.normalized().toRotationMatrix();
      link.parent_T_child.translation() = Eigen::Vector3d(number(2), number(3), number(4));
      out_.by_child[child] = link;
    }
  }

  StaticTransforms result() const {
    if (!decoder_) {
      throw_topic_not_in_bag(frames_.where, frames_.topic, names_);
    }
    return out_;
  }

 private:
  const FramesSource& frames_;
  std::string bag_, names_;
  std::optional<MessageDecoder> decoder_;
  std::size_t index_{}, messages_{};
  DecodedFields fields_;
  StaticTransforms out_;
};

// root_T_frame and the root it reaches, following parents (a loop stops at the frame met again).
std::pair<std::string, Eigen::Isometry3d> to_root(const StaticTransforms& tf, std::string frame) {
  Eigen::Isometry3d root_T_frame = Eigen::Isometry3d::Identity();
  std::vector<std::string> seen;
  for (auto it = tf.by_child.find(frame); it != tf.by_child.end(); it = tf.by_child.find(frame)) {
    if (std::find(seen.begin(), seen.end(), frame) != seen.end()) break;
    seen.push_back(frame);
    root_T_frame = it->second.parent_T_child * root_T_frame;
    frame = it->second.parent;
  }
  return {frame, root_T_frame};
}

std::string known_frames(const StaticTransforms& tf) {
  std::string out;
  for (const auto& [child, link] : tf.by_child) {
    for (const std::string& name : {link.parent, child})
      if (out.find("'" + name + "'") == std::string::npos)
        out += (out.empty() ? "" : ", ") + ("'" + name + "'");
  }
  return out.empty() ? "none" : out;
}

}  // namespace

Eigen::Isometry3d StaticTransforms::base_T(const std::string& base, const std::string& frame,
                                           const InputLocation& where) const {
  const bool known = by_child.contains(frame) ||
                     std::any_of(by_child.begin(), by_child.end(),
                                 [&](const auto& entry) { return entry.second.parent == frame; });
  if (!known) {
    throw InputError(where,
                     fmt::format("tf has no frame '{}' (it has {})", frame, known_frames(*this)));
  }
  const auto [frame_root, root_T_frame] = to_root(*this, frame);
  const auto [base_root, root_T_base] = to_root(*this, base);
  if (frame_root != base_root) {
    throw InputError(where, fmt::format("tf does not connect frame '{}' to '{}' (their roots: "
                                        "'{}', '{}')",
                                        frame, base, frame_root, base_root));
  }
  return root_T_base.inverse() * root_T_frame;
}

StaticTransforms read_static_transforms(const std::filesystem::path& bag_path,
                                        const FramesSource& frames) {
  TransformVisitor visitor(frames, bag_path.string());
  read_bag(bag_path, visitor);
  return visitor.result();
}

TopicMap with_static_transforms(TopicMap map, const StaticTransforms& transforms) {
  if (!map.frames) return map;
  const FramesSource& frames = *map.frames;
  if (!frames.imu.empty()) {
    const Eigen::Isometry3d base_T_imu =
        transforms.base_T(frames.base, frames.imu, {map.file, 0, "frames.imu"});
    map.imu->body_R_sensor = base_T_imu.linear();
    map.vehicle.imu_position_m = base_T_imu.translation().head<2>();
    if (map.heading && map.heading->topic == map.imu->topic && !map.heading_mounting_stated)
      map.heading->body_R_sensor = base_T_imu.linear();
  }
  if (!frames.gnss.empty()) {
    map.vehicle.gnss_position_m =
        transforms.base_T(frames.base, frames.gnss, {map.file, 0, "frames.gnss"})
            .translation()
            .head<2>();
  }
  return map;
}

}  // namespace odocal::bag
