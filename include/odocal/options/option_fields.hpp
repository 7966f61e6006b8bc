#pragma once
// One table per options struct describes each of its fields once: key, unit, accepted range and
// a one-line doc; the default is the struct's own initialiser. The table drives validate(), the
// YAML reader, the JSON writer and `--print-config`, so an option is written in one place.

#include <Eigen/Core>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <variant>

#include "odocal/options/enum_names.hpp"

namespace odocal {

// Access to an enum member by its names (the table cannot hold a pointer to an enum member of
// unknown type).
template <typename Options>
struct EnumMember {
  const char* (*get)(const Options&);
  bool (*set)(Options&, std::string_view);  // false: not one of the names
  std::string (*choices)();                 // "a | b | c"
  std::string (*expected)();                // "a, b or c"
};

template <auto member, typename Options, typename Enum>
constexpr EnumMember<Options> enum_member_of(Enum Options::*) {
  return {[](const Options& o) { return enum_name(o.*member); },
          [](Options& o, std::string_view name) {
            const auto value = parse_enum<Enum>(name);
            if (value) o.*member = *value;
            return value.has_value();
          },
          &enum_choices<Enum>, &enum_expected<Enum>};
}

// enum_member<&Options::field>(): the EnumMember of an enum-typed field.
template <auto member>
constexpr auto enum_member() {
  return enum_member_of<member>(member);
}

template <typename Options>
struct OptionField {
  using Member = std::variant<double Options::*, int Options::*, std::size_t Options::*,
                              bool Options::*, Eigen::Vector3d Options::*, EnumMember<Options>>;
  const char* key;   // YAML and JSON key
  const char* unit;  // "m", "rad", "1" for dimensionless; "" for flags and names
  double min;        // accepted range, inclusive; numbers and each vector element
  double max;
  const char* doc;  // one line
  Member member;
};

template <typename Options>
using OptionTable = std::span<const OptionField<Options>>;

// The shortest text that reads back as the same double ("0.01", "1e+06", "inf").
std::string format_option_number(double value);

// Empty when every numeric field of `options` is finite and inside its range, else the first
// field that is not, in words.
template <typename Options>
std::string check_option_ranges(OptionTable<Options> table, const Options& options) {
  for (const OptionField<Options>& field : table) {
    const auto outside = [&](double value) { return !(value >= field.min && value <= field.max); };
    const auto message = [&](double value) {
      return std::string(field.key) + " = " + format_option_number(value) +
             " is out of range: expected " + format_option_number(field.min) + " to " +
             format_option_number(field.max);
    };
    if (const auto* d = std::get_if<double Options::*>(&field.member)) {
      if (outside(options.**d)) return message(options.**d);
    } else if (const auto* i = std::get_if<int Options::*>(&field.member)) {
      if (outside(options.**i)) return message(options.**i);
    } else if (const auto* n = std::get_if<std::size_t Options::*>(&field.member)) {
      if (outside(static_cast<double>(options.**n)))
        return message(static_cast<double>(options.**n));
    } else if (const auto* v = std::get_if<Eigen::Vector3d Options::*>(&field.member)) {
      for (int k = 0; k < 3; ++k)
        if (outside((options.**v)(k))) return message((options.**v)(k));
    }
  }
  return "";
}

}  // namespace odocal
