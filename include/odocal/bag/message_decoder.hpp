#pragma once
// Decoding ROS messages without generated code: a message definition (the text a ROS 1
// connection record or an MCAP schema carries, "ros1msg"/"ros2msg"; odocal's own definitions of
// the common sensor, geometry, navigation and std types where the bag carries none) is parsed
// once, the fields a caller asks for by path ("angular_velocity.z", "header.stamp", "name") are
// compiled into a walk, and each message is decoded by that walk: ROS 1 serialisation (packed
// little-endian) or CDR (ROS 2: 4-byte encapsulation header, little- or big-endian, fields
// aligned to their size).

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace odocal::bag {

enum class MessageEncoding { kRos1, kCdr };

// "ros1" or "cdr" (the bag's serialisation format); InputError for any other.
MessageEncoding message_encoding_from_name(std::string_view name, const std::string& source);

// "sensor_msgs/msg/Imu" -> "sensor_msgs/Imu".
std::string canonical_type_name(std::string_view type);

// Values of the requested fields in one message, one entry per path: a number field gives one
// value, an array its elements (a path through an array of messages gives one per element), a
// time or duration (ROS 1 primitive or builtin_interfaces message) its seconds; string fields go
// to `strings`.
struct DecodedFields {
  std::vector<std::vector<double>> numbers;
  std::vector<std::vector<std::string>> strings;
};

class MessageDecoder {
 public:
  // `type` as the bag names it; `definition` the text it carries (may be empty) in
  // `definition_format` ("ros1msg", "ros2msg" or ""). When the carried text does not parse or
  // misses a type, odocal's own definition of `type` is used, if it has one. `source` names the
  // bag and topic in errors. Throws InputError when the type cannot be resolved or a path does not
  // name a field (the message lists the fields there are).
  MessageDecoder(std::string_view type, std::string_view definition,
                 std::string_view definition_format, MessageEncoding encoding,
                 const std::vector<std::string>& paths, const std::string& source);
  ~MessageDecoder();
  MessageDecoder(MessageDecoder&&) noexcept;
  MessageDecoder& operator=(MessageDecoder&&) noexcept;

  // Decodes `data`; throws DecodeError (the problem only) when it is truncated, has a count
  // larger than its bytes, or an unsupported encapsulation.
  void decode(std::span<const std::uint8_t> data, DecodedFields& out) const;

  // Whether the string path `index` holds strings (else numbers).
  bool is_string_path(std::size_t index) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class DecodeError : public std::exception {
 public:
  explicit DecodeError(std::string problem) : problem_(std::move(problem)) {}
  const char* what() const noexcept override { return problem_.c_str(); }

 private:
  std::string problem_;
};

}  // namespace odocal::bag
