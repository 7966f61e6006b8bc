#include "odocal/bag/message_decoder.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <optional>

#include "message_types.hpp"
#include "odocal/error.hpp"

namespace odocal::bag {
namespace {

std::size_t primitive_size(Primitive primitive) {
  switch (primitive) {
    case Primitive::kBool:
    case Primitive::kInt8:
    case Primitive::kUint8:
      return 1;
    case Primitive::kInt16:
    case Primitive::kUint16:
      return 2;
    case Primitive::kInt32:
    case Primitive::kUint32:
    case Primitive::kFloat32:
      return 4;
    case Primitive::kInt64:
    case Primitive::kUint64:
    case Primitive::kFloat64:
    case Primitive::kTime:
    case Primitive::kDuration:
      return 8;
    default:
      return 0;  // variable size
  }
}

// Which fields of one type a walk records (slot >= 0) or descends into (child).
struct Selection {
  std::vector<int> slot;                             // per field, -1: not recorded
  std::vector<std::unique_ptr<Selection>> children;  // per field, null: not descended into
};

// Reads one serialised message: ROS 1 packed, or CDR with alignment relative to the payload.
class Reader {
 public:
  Reader(std::span<const std::uint8_t> bytes, bool cdr, bool big_endian)
      : data_(bytes.data()), size_(bytes.size()), cdr_(cdr), swap_(big_endian) {}

  std::size_t position() const { return position_; }

  void align(std::size_t size) {
    if (!cdr_ || size <= 1) return;
    position_ = (position_ + size - 1) & ~(size - 1);
  }

  void require(std::uint64_t bytes, const char* what) const {
    if (position_ > size_ || bytes > size_ - position_) {
      throw DecodeError(
          fmt::format("truncated message: {} needs {} bytes at byte {}, message "
                      "has {}",
                      what, bytes, position_, size_));
    }
  }

  template <class T>
  T read(const char* what) {
    align(sizeof(T));
    require(sizeof(T), what);
    T value;
    std::memcpy(&value, data_ + position_, sizeof(T));
    position_ += sizeof(T);
    if (swap_ && sizeof(T) > 1) value = swapped(value);
    return value;
  }

  void skip(std::uint64_t count, std::size_t element_size, const char* what) {
    align(element_size);
    if (element_size != 0 && count > (size_ - std::min(position_, size_)) / element_size)
      require(count * element_size, what);  // throws
    position_ += static_cast<std::size_t>(count * element_size);
  }

  // A count of elements of `element_size` bytes (strings: at least 4) that cannot fit in the
  // message is refused before anything is allocated for it.
  void check_fits(std::uint64_t count, std::size_t element_size) const {
    if (count > size_ / std::max<std::size_t>(element_size, 1)) {
      throw DecodeError(fmt::format("array of {} elements in a message of {} bytes", count, size_));
    }
  }

  std::string_view text(std::uint32_t length) {
    require(length, "string");
    std::string_view out(reinterpret_cast<const char*>(data_ + position_), length);
    position_ += length;
    return out;
  }

  bool cdr() const { return cdr_; }

 private:
  template <class T>
  static T swapped(T value) {
    std::array<std::uint8_t, sizeof(T)> bytes;
    std::memcpy(bytes.data(), &value, sizeof(T));
    std::reverse(bytes.begin(), bytes.end());
    std::memcpy(&value, bytes.data(), sizeof(T));
    return value;
  }

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_{};
  bool cdr_;
  bool swap_;
};

}  // namespace

struct MessageDecoder::Impl {
  MessageTypes types;
  MessageEncoding encoding{};
  Selection root;
  std::vector<bool> string_paths;

  void walk(std::size_t type_index, const Selection* selection, Reader& reader,
            DecodedFields& out) const {
    const TypeSpec& type = types.types[type_index];
    if (type.fields.empty() && reader.cdr()) {
      reader.skip(1, 1, "empty structure");  // CDR gives an empty message one dummy byte
      return;
    }
    for (std::size_t f = 0; f < type.fields.size(); ++f) {
      const FieldSpec& field = type.fields[f];
      const int slot = selection ? selection->slot[f] : -1;
      const Selection* child = selection ? selection->children[f].get() : nullptr;
      std::uint64_t count = 1;
      if (field.array == ArrayKind::kFixed) {
        count = field.length;
      } else if (field.array != ArrayKind::kNone) {
        count = reader.read<std::uint32_t>("array length");
        if (field.array == ArrayKind::kBounded && count > field.length) {
          throw DecodeError(fmt::format("field {}: {} elements, more than its bound {}", field.name,
                                        count, field.length));
        }
      }
      if (field.primitive == Primitive::kMessage) {
        const TypeSpec& nested = types.types[field.message_type];
        for (std::uint64_t i = 0; i < count; ++i) {
          if (slot >= 0 && nested.is_time) {
            const auto seconds = reader.read<std::int32_t>("time seconds");
            const auto nanoseconds = reader.read<std::uint32_t>("time nanoseconds");
            out.numbers[slot].push_back(seconds + nanoseconds * 1e-9);
          } else {
            walk(field.message_type, child, reader, out);
          }
        }
      } else if (slot >= 0) {
        read_values(field.primitive, count, reader, out, static_cast<std::size_t>(slot));
      } else {
        skip_values(field.primitive, count, reader);
      }
    }
  }

  void skip_values(Primitive primitive, std::uint64_t count, Reader& reader) const {
    if (primitive == Primitive::kTime || primitive == Primitive::kDuration) {
      reader.skip(2 * count, 4, "array");  // two 4-byte words each
      return;
    }
    if (const std::size_t size = primitive_size(primitive); size != 0) {
      reader.skip(count, size, "array");
      return;
    }
    for (std::uint64_t i = 0; i < count; ++i) read_string(primitive, reader);
  }

  std::string_view read_string(Primitive primitive, Reader& reader) const {
    if (primitive == Primitive::kWString) throw DecodeError("wstring fields are not decoded");
    const auto length = reader.read<std::uint32_t>("string length");
    std::string_view text = reader.text(length);
    // CDR strings count and carry their terminating NUL.
    if (reader.cdr() && !text.empty() && text.back() == '\0') text.remove_suffix(1);
    return text;
  }

  void read_values(Primitive primitive, std::uint64_t count, Reader& reader, DecodedFields& out,
                   std::size_t slot) const {
    if (primitive == Primitive::kString || primitive == Primitive::kWString) {
      reader.check_fits(count, 4);
      for (std::uint64_t i = 0; i < count; ++i)
        out.strings[slot].emplace_back(read_string(primitive, reader));
      return;
    }
    std::vector<double>& values = out.numbers[slot];
    reader.check_fits(count, primitive_size(primitive));  // before reserving room for them
    values.reserve(values.size() + static_cast<std::size_t>(count));
    for (std::uint64_t i = 0; i < count; ++i) values.push_back(read_number(primitive, reader));
  }

  static double read_number(Primitive primitive, Reader& reader) {
    switch (primitive) {
      case Primitive::kBool:
      case Primitive::kUint8:
        return reader.read<std::uint8_t>("uint8");
      case Primitive::kInt8:
        return reader.read<std::int8_t>("int8");
      case Primitive::kInt16:
        return reader.read<std::int16_t>("int16");
      case Primitive::kUint16:
        return reader.read<std::uint16_t>("uint16");
      case Primitive::kInt32:
        return reader.read<std::int32_t>("int32");
      case Primitive::kUint32:
        return reader.read<std::uint32_t>("uint32");
      case Primitive::kInt64:
        return static_cast<double>(reader.read<std::int64_t>("int64"));
      case Primitive::kUint64:
        return static_cast<double>(reader.read<std::uint64_t>("uint64"));
      case Primitive::kFloat32:
        return reader.read<float>("float32");
      case Primitive::kFloat64:
        return reader.read<double>("float64");
      case Primitive::kTime:
      case Primitive::kDuration: {
        const auto seconds = reader.read<std::int32_t>("time seconds");
        const auto nanoseconds = reader.read<std::int32_t>("time nanoseconds");
        return seconds + nanoseconds * 1e-9;
      }
      default:
        throw DecodeError("not a number field");
    }
  }
};

MessageEncoding message_encoding_from_name(std::string_view name, const std::string& source) {
  if (name == "ros1") return MessageEncoding::kRos1;
  if (name == "cdr") return MessageEncoding::kCdr;
  throw InputError(
      {source, 0, ""},
      fmt::format("message encoding '{}' is not decoded (odocal reads ros1 and cdr)", name));
}

namespace {

std::string field_names(const TypeSpec& type) {
  std::string out;
  for (const FieldSpec& field : type.fields) out += (out.empty() ? "" : ", ") + field.name;
  return out.empty() ? "none" : out;
}

MessageTypes types_for(std::string_view type, std::string_view definition,
                       std::string_view definition_format, MessageEncoding encoding,
                       const std::string& source) {
  const bool carried = definition_format == "ros1msg" || definition_format == "ros2msg";
  if (carried) {
    try {
      return parse_message_types(type, definition, encoding, source);
    } catch (const InputError&) {
      // A broken carried definition (rosbag2 has written some): odocal's own, if it has one.
      if (builtin_definition(canonical_type_name(type), encoding).empty()) throw;
    }
  }
  return parse_message_types(type, "", encoding, source);
}

}  // namespace

MessageDecoder::MessageDecoder(std::string_view type, std::string_view definition,
                               std::string_view definition_format, MessageEncoding encoding,
                               const std::vector<std::string>& paths, const std::string& source)
    : impl_(std::make_unique<Impl>()) {
  impl_->encoding = encoding;
  impl_->types = types_for(type, definition, definition_format, encoding, source);
  const auto make_selection = [&](std::size_t type_index) {
    auto selection = std::make_unique<Selection>();
    const std::size_t fields = impl_->types.types[type_index].fields.size();
    selection->slot.assign(fields, -1);
    selection->children.resize(fields);
    return selection;
  };
  impl_->root = std::move(*make_selection(0));
  for (std::size_t p = 0; p < paths.size(); ++p) {
    Selection* selection = &impl_->root;
    std::size_t type_index = 0;
    std::string_view rest = paths[p];
    while (true) {
      const auto dot = rest.find('.');
      const std::string_view name = rest.substr(0, dot);
      const TypeSpec& spec = impl_->types.types[type_index];
      std::size_t f = 0;
      while (f < spec.fields.size() && spec.fields[f].name != name) ++f;
      if (f == spec.fields.size()) {
        throw InputError({source, 0, paths[p]}, fmt::format("{} has no field '{}' (it has {})",
                                                            spec.name, name, field_names(spec)));
      }
      const FieldSpec& field = spec.fields[f];
      if (dot == std::string_view::npos) {
        const bool is_message = field.primitive == Primitive::kMessage;
        if (is_message && !impl_->types.types[field.message_type].is_time) {
          throw InputError({source, 0, paths[p]},
                           fmt::format("field '{}' is a {} message; name one of its fields ({})",
                                       name, field.message_type_name,
                                       field_names(impl_->types.types[field.message_type])));
        }
        if (selection->slot[f] >= 0 || selection->children[f]) {
          throw InputError({source, 0, paths[p]}, "the same field is asked for twice");
        }
        selection->slot[f] = static_cast<int>(p);
        impl_->string_paths.resize(paths.size());
        impl_->string_paths[p] =
            field.primitive == Primitive::kString || field.primitive == Primitive::kWString;
        break;
      }
      if (field.primitive != Primitive::kMessage ||
          impl_->types.types[field.message_type].is_time) {
        throw InputError({source, 0, paths[p]},
                         fmt::format("field '{}' of {} is not a message", name, spec.name));
      }
      if (selection->slot[f] >= 0)
        throw InputError({source, 0, paths[p]}, "the same field is asked for twice");
      if (!selection->children[f]) selection->children[f] = make_selection(field.message_type);
      selection = selection->children[f].get();
      type_index = field.message_type;
      rest = rest.substr(dot + 1);
    }
  }
  impl_->string_paths.resize(paths.size());
}

MessageDecoder::~MessageDecoder() = default;
MessageDecoder::MessageDecoder(MessageDecoder&&) noexcept = default;
MessageDecoder& MessageDecoder::operator=(MessageDecoder&&) noexcept = default;

bool MessageDecoder::is_string_path(std::size_t index) const {
  return impl_->string_paths.at(index);
}

void MessageDecoder::decode(std::span<const std::uint8_t> data, DecodedFields& out) const {
  const std::size_t paths = impl_->string_paths.size();
  out.numbers.resize(paths);
  out.strings.resize(paths);
  for (auto& values : out.numbers) values.clear();
  for (auto& values : out.strings) values.clear();
  bool big_endian = false;
  if (impl_->encoding == MessageEncoding::kCdr) {
    if (data.size() < 4) throw DecodeError("truncated message: no CDR encapsulation header");
    // Encapsulation kinds: 0x0000 CDR big-endian, 0x0001 CDR little-endian (XCDR1); the later
    // XCDR2 kinds are not written by ROS 2's default middleware.
    if (data[0] != 0 || data[1] > 1)
      throw DecodeError(
          fmt::format("CDR encapsulation 0x{:02x}{:02x} is not decoded (odocal "
                      "reads plain CDR)",
                      data[0], data[1]));
    big_endian = data[1] == 0;
    data = data.subspan(4);
  }
  Reader reader(data, impl_->encoding == MessageEncoding::kCdr, big_endian);
  impl_->walk(0, &impl_->root, reader, out);
}

}  // namespace odocal::bag
