#pragma once
// Parsed ROS message definitions: each type a list of fields, each field a primitive or another
// type, alone or as an array (fixed, bounded or unbounded).

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "odocal/bag/message_decoder.hpp"

namespace odocal::bag {

enum class Primitive : std::uint8_t {
  kBool,
  kInt8,
  kUint8,
  kInt16,
  kUint16,
  kInt32,
  kUint32,
  kInt64,
  kUint64,
  kFloat32,
  kFloat64,
  kString,
  kWString,
  kTime,
  kDuration,
  kMessage
};

enum class ArrayKind : std::uint8_t { kNone, kFixed, kBounded, kDynamic };

struct FieldSpec {
  std::string name;
  Primitive primitive{};
  std::string message_type_name;  // canonical, when primitive == kMessage
  std::size_t message_type{};     // index into MessageTypes::types when primitive == kMessage
  ArrayKind array{ArrayKind::kNone};
  std::uint32_t length{};  // kFixed: the count; kBounded: the bound
};

struct TypeSpec {
  std::string name;  // canonical: "sensor_msgs/Imu"
  std::vector<FieldSpec> fields;
  bool is_time{};  // builtin_interfaces/Time or Duration: decoded as seconds when asked for
};

struct MessageTypes {
  std::vector<TypeSpec> types;  // types[0] is the root
};

// Parses `definition` (root type's fields, then "=====" separated "MSG: pkg/Type" sections) and
// resolves every type it uses, from the text first, then from odocal's own definitions. Throws
// InputError (file `source`) naming the line or the missing type.
MessageTypes parse_message_types(std::string_view root_type, std::string_view definition,
                                 MessageEncoding encoding, const std::string& source);

// odocal's own definition of `type` (canonical name) for `encoding`; empty when it has none.
std::string_view builtin_definition(std::string_view type, MessageEncoding encoding);

}  // namespace odocal::bag
