#pragma once
// One name table per enum: the spelling used in YAML and JSON, on the command line and in
// reports. Specialise EnumNames<E> beside the enum with
//   static constexpr std::array<EnumName<E>, N> kTable{{{E::kA, "a"}, ...}};
// and every reader, writer and message takes its names from there.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace odocal {

template <typename Enum>
struct EnumName {
  Enum value;
  const char* name;
};

template <typename Enum>
struct EnumNames;  // specialised per enum

template <typename Enum>
constexpr const char* enum_name(Enum value) {
  for (const EnumName<Enum>& entry : EnumNames<Enum>::kTable)
    if (entry.value == value) return entry.name;
  return "?";  // unreachable for a value of the enum
}

template <typename Enum>
constexpr std::optional<Enum> parse_enum(std::string_view name) {
  for (const EnumName<Enum>& entry : EnumNames<Enum>::kTable)
    if (name == entry.name) return entry.value;
  return std::nullopt;
}

// "a, b or c": what a reader expected when the name was not one of them.
template <typename Enum>
std::string enum_expected() {
  std::string text;
  const auto& table = EnumNames<Enum>::kTable;
  for (std::size_t i = 0; i < table.size(); ++i) {
    if (i > 0) text += i + 1 == table.size() ? " or " : ", ";
    text += table[i].name;
  }
  return text;
}

// Every name, in table order (e.g. for a command line's list of choices).
template <typename Enum>
std::vector<std::string> enum_name_list() {
  std::vector<std::string> names;
  for (const EnumName<Enum>& entry : EnumNames<Enum>::kTable) names.emplace_back(entry.name);
  return names;
}

// "a | b | c": the choices, for documentation and --print-config.
template <typename Enum>
std::string enum_choices() {
  std::string text;
  for (const EnumName<Enum>& entry : EnumNames<Enum>::kTable) {
    if (!text.empty()) text += " | ";
    text += entry.name;
  }
  return text;
}

}  // namespace odocal
