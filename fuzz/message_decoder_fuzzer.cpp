// The message decoder on arbitrary bytes. First byte: bit 0 picks ROS 1 or CDR; bit 1 picks a
// type of odocal's own definitions (the rest is one message, every import field asked for) or a
// definition text (up to the first NUL) followed by one message, all fields walked.

#include <array>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "odocal/bag/message_decoder.hpp"

namespace {

using odocal::bag::MessageDecoder;
using odocal::bag::MessageEncoding;

struct Known {
  const char* type;
  std::vector<std::string> paths;
};

const std::array<Known, 5> kKnown = {{
    {"sensor_msgs/msg/Imu",
     {"header.stamp", "header.frame_id", "orientation.w", "angular_velocity.z",
      "linear_acceleration.x"}},
    {"sensor_msgs/msg/NavSatFix",
     {"header.stamp", "latitude", "position_covariance", "status.status"}},
    {"sensor_msgs/msg/JointState", {"header.stamp", "name", "position", "velocity"}},
    {"nav_msgs/msg/Odometry",
     {"header.stamp", "child_frame_id", "twist.twist.linear.x", "twist.twist.angular.z",
      "twist.covariance"}},
    {"geometry_msgs/msg/TwistStamped", {"header.stamp", "twist.linear.x"}},
}};

void decode(const MessageDecoder& decoder, std::string_view bytes) {
  odocal::bag::DecodedFields fields;
  try {
    decoder.decode({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()}, fields);
  } catch (const odocal::bag::DecodeError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const MessageEncoding encoding = (data[0] & 1) ? MessageEncoding::kCdr : MessageEncoding::kRos1;
  const std::string_view rest = odocal::fuzz::as_text(data + 2, size - 2);
  odocal::fuzz::expect_only_odocal_errors([&] {
    if (data[0] & 2) {
      const Known& known = kKnown[data[1] % kKnown.size()];
      decode(MessageDecoder(known.type, "", "", encoding, known.paths, "fuzz"), rest);
      return;
    }
    const auto nul = rest.find('\0');
    const std::string_view definition = rest.substr(0, nul);
    const std::string_view message =
        nul == std::string_view::npos ? std::string_view{} : rest.substr(nul + 1);
    decode(MessageDecoder("fuzz_msgs/msg/Root", definition,
                          encoding == MessageEncoding::kCdr ? "ros2msg" : "ros1msg", encoding, {},
                          "fuzz"),
           message);
  });
  return 0;
}
