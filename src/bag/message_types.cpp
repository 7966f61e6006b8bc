// The .msg grammar as ROS 1 and ROS 2 write it into bags: one field per line
// "<type>[array] <name> [default]", constants "<type> NAME=value", comments after '#', and the
// definitions of the types used appended in sections that start with a line of '=' and
// "MSG: <package>/<Type>".

#include "message_types.hpp"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <map>
#include <optional>

#include "odocal/error.hpp"

namespace odocal::bag {
namespace {

std::string_view trim(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::optional<Primitive> primitive_of(std::string_view name, MessageEncoding encoding) {
  static const std::map<std::string_view, Primitive> kTable = {
      {"bool", Primitive::kBool},        {"int8", Primitive::kInt8},
      {"uint8", Primitive::kUint8},      {"int16", Primitive::kInt16},
      {"uint16", Primitive::kUint16},    {"int32", Primitive::kInt32},
      {"uint32", Primitive::kUint32},    {"int64", Primitive::kInt64},
      {"uint64", Primitive::kUint64},    {"float32", Primitive::kFloat32},
      {"float64", Primitive::kFloat64},  {"string", Primitive::kString},
      {"wstring", Primitive::kWString},  {"time", Primitive::kTime},
      {"duration", Primitive::kDuration}};
  if (name == "byte")
    return encoding == MessageEncoding::kRos1 ? Primitive::kInt8 : Primitive::kUint8;
  if (name == "char") return Primitive::kUint8;
  const auto it = kTable.find(name);
  if (it == kTable.end()) return std::nullopt;
  return it->second;
}

std::string package_of(std::string_view type) {
  const auto slash = type.find('/');
  return std::string(slash == std::string_view::npos ? std::string_view{} : type.substr(0, slash));
}

// The unparsed fields of each type found in a definition text, by canonical name.
using Sections = std::map<std::string, std::string_view, std::less<>>;

Sections split_sections(std::string_view root, std::string_view text) {
  Sections sections;
  std::string current(root);
  std::size_t section_start = 0;
  std::size_t position = 0;
  while (position <= text.size()) {
    const auto end = std::min(text.find('\n', position), text.size());
    const std::string_view line = trim(text.substr(position, end - position));
    if (line.size() >= 3 && line.find_first_not_of('=') == std::string_view::npos) {
      sections.try_emplace(current, text.substr(section_start, position - section_start));
      // The next non-empty line names the type: "MSG: pkg/Type".
      std::size_t next = end + 1;
      while (next < text.size()) {
        const auto next_end = std::min(text.find('\n', next), text.size());
        const std::string_view header = trim(text.substr(next, next_end - next));
        next = next_end + 1;
        if (header.empty()) continue;
        current = header.starts_with("MSG:") ? canonical_type_name(trim(header.substr(4))) : "";
        break;
      }
      section_start = std::min(next, text.size());
      position = section_start;
      continue;
    }
    position = end + 1;
  }
  sections.try_emplace(current, text.substr(section_start));
  return sections;
}

class TypeResolver {
 public:
  TypeResolver(Sections sections, MessageEncoding encoding, const std::string& source)
      : sections_(std::move(sections)), encoding_(encoding), source_(source) {}

  MessageTypes resolve(const std::string& root) {
    resolve_type(root, "");
    return std::move(types_);
  }

 private:
  std::size_t resolve_type(const std::string& name, std::string_view used_by) {
    if (const auto known = index_.find(name); known != index_.end()) {
      if (known->second == kInProgress) fail(fmt::format("type {} contains itself", name));
      return known->second;
    }
    std::string_view text;
    if (const auto section = sections_.find(name); section != sections_.end()) {
      text = section->second;
    } else {
      text = builtin_definition(name, encoding_);
      if (text.empty()) {
        fail(used_by.empty()
                 ? fmt::format("no definition of type {} in the bag, and odocal has none", name)
                 : fmt::format("type {} (used by {}) has no definition in the bag, and odocal "
                               "has none",
                               name, used_by));
      }
    }
    index_[name] = kInProgress;
    TypeSpec type;
    type.name = name;
    type.is_time = name == "builtin_interfaces/Time" || name == "builtin_interfaces/Duration";
    parse_fields(text, type);
    const std::size_t index = types_.types.size();
    types_.types.push_back(std::move(type));
    // Nested types are resolved after the parent took its slot (the root stays at 0).
    for (std::size_t f = 0; f < types_.types[index].fields.size(); ++f) {
      if (types_.types[index].fields[f].primitive != Primitive::kMessage) continue;
      const std::string nested = types_.types[index].fields[f].message_type_name;
      const std::size_t nested_index = resolve_type(nested, name);
      types_.types[index].fields[f].message_type = nested_index;
    }
    index_[name] = index;
    return index;
  }

  void parse_fields(std::string_view text, TypeSpec& type) {
    std::size_t position = 0;
    std::size_t line_number = 0;
    while (position < text.size()) {
      const auto end = std::min(text.find('\n', position), text.size());
      std::string_view line = text.substr(position, end - position);
      position = end + 1;
      ++line_number;
      const auto comment = line.find('#');
      const bool may_be_string_constant = line.find('=') != std::string_view::npos;
      if (comment != std::string_view::npos && !may_be_string_constant)
        line = line.substr(0, comment);
      line = trim(line);
      if (line.empty() || line.front() == '#') continue;
      const auto split = line.find_first_of(" \t");
      if (split == std::string_view::npos)
        fail_line(type, line_number, fmt::format("expected '<type> <name>', got '{}'", line));
      const std::string_view type_token = line.substr(0, split);
      const std::string_view rest = trim(line.substr(split));
      const auto name_end = rest.find_first_of(" \t=");
      const std::string_view name = rest.substr(0, name_end);
      const std::string_view after =
          name_end == std::string_view::npos ? std::string_view{} : trim(rest.substr(name_end));
      if (!after.empty() && after.front() == '=') continue;  // a constant: not serialised
      if (name.empty() || !std::isalpha(static_cast<unsigned char>(name.front())) ||
          name.find_first_not_of(
              "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_") !=
              std::string_view::npos) {
        fail_line(type, line_number, fmt::format("'{}' is not a field name", name));
      }
      type.fields.push_back(parse_field_type(type_token, name, type, line_number));
    }
  }

  FieldSpec parse_field_type(std::string_view token, std::string_view name, const TypeSpec& type,
                             std::size_t line_number) const {
    FieldSpec field;
    field.name = std::string(name);
    std::string_view base = token;
    if (token.ends_with(']')) {
      const auto open = token.rfind('[');
      if (open == std::string_view::npos)
        fail_line(type, line_number, fmt::format("bad array type '{}'", token));
      std::string_view inner = token.substr(open + 1, token.size() - open - 2);
      base = token.substr(0, open);
      if (inner.empty()) {
        field.array = ArrayKind::kDynamic;
      } else {
        field.array = ArrayKind::kFixed;
        if (inner.starts_with("<=")) {
          field.array = ArrayKind::kBounded;
          inner.remove_prefix(2);
        }
        const auto [end, error] =
            std::from_chars(inner.data(), inner.data() + inner.size(), field.length);
        if (error != std::errc{} || end != inner.data() + inner.size())
          fail_line(type, line_number, fmt::format("bad array length in '{}'", token));
      }
    }
    if (const auto bound = base.find("<="); bound != std::string_view::npos)
      base = base.substr(0, bound);  // a bounded string reads as a string
    if (const auto primitive = primitive_of(base, encoding_)) {
      field.primitive = *primitive;
      return field;
    }
    field.primitive = Primitive::kMessage;
    if (base.find('/') != std::string_view::npos) {
      field.message_type_name = canonical_type_name(base);
    } else if (base == "Header") {
      field.message_type_name = "std_msgs/Header";
    } else {
      field.message_type_name = package_of(type.name) + "/" + std::string(base);
    }
    return field;
  }

  [[noreturn]] void fail_line(const TypeSpec& type, std::size_t line_number,
                              const std::string& problem) const {
    fail(fmt::format("definition of {}, line {}: {}", type.name, line_number, problem));
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError({source_, 0, ""}, problem);
  }

  static constexpr std::size_t kInProgress = static_cast<std::size_t>(-1);
  Sections sections_;
  MessageEncoding encoding_;
  const std::string& source_;
  MessageTypes types_;
  std::map<std::string, std::size_t, std::less<>> index_;
};

}  // namespace

MessageTypes parse_message_types(std::string_view root_type, std::string_view definition,
                                 MessageEncoding encoding, const std::string& source) {
  const std::string root = canonical_type_name(root_type);
  Sections sections;
  if (!trim(definition).empty()) sections = split_sections(root, definition);
  return TypeResolver(std::move(sections), encoding, source).resolve(root);
}

std::string canonical_type_name(std::string_view type) {
  std::string out(trim(type));
  const auto marker = out.find("/msg/");
  if (marker != std::string::npos) out.erase(marker, 4);
  return out;
}

}  // namespace odocal::bag
