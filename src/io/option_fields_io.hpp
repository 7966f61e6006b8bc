#pragma once
// An options struct's field table (odocal/options/option_fields.hpp) read from a YAML mapping,
// written into JSON, and printed as commented YAML: the one place that turns a table into text.

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "odocal/error.hpp"
#include "odocal/io/text_output.hpp"
#include "odocal/options/option_fields.hpp"
#include "yaml_map.hpp"

namespace odocal::detail {

// Reads every field present in `map` into `options` (absent keys keep their value); a bad value
// is an InputError naming file, line and key. Does not reject unknown keys: a mapping may hold
// several tables' fields.
template <typename Options>
void read_option_fields(YamlMap& map, OptionTable<Options> table, Options& options) {
  for (const OptionField<Options>& field : table) {
    const std::string key = field.key;
    if (const auto* d = std::get_if<double Options::*>(&field.member)) {
      map.read(key, options.**d, field.min, field.max);
    } else if (const auto* i = std::get_if<int Options::*>(&field.member)) {
      map.read(key, options.**i, static_cast<int>(field.min), static_cast<int>(field.max));
    } else if (const auto* n = std::get_if<std::size_t Options::*>(&field.member)) {
      double value = static_cast<double>(options.**n);
      map.read(key, value, field.min, field.max);
      if (value != std::round(value)) throw InputError(map.location(key), "expected an integer");
      options.** n = static_cast<std::size_t>(value);
    } else if (const auto* b = std::get_if<bool Options::*>(&field.member)) {
      map.read(key, options.**b);
    } else if (const auto* v = std::get_if<Eigen::Vector3d Options::*>(&field.member)) {
      map.read(key, options.**v, field.min, field.max);
    } else if (const auto* e = std::get_if<EnumMember<Options>>(&field.member)) {
      std::string name = e->get(options);
      map.read(key, name);
      if (!e->set(options, name)) throw InputError(map.location(key), "expected " + e->expected());
    }
  }
}

template <typename Options>
nlohmann::json option_value_json(const OptionField<Options>& field, const Options& options) {
  return std::visit(
      [&](const auto& member) -> nlohmann::json {
        using Member = std::decay_t<decltype(member)>;
        if constexpr (std::is_same_v<Member, EnumMember<Options>>) {
          return member.get(options);
        } else if constexpr (std::is_same_v<Member, Eigen::Vector3d Options::*>) {
          const Eigen::Vector3d& v = options.*member;
          return nlohmann::json::array({v(0), v(1), v(2)});
        } else {
          return options.*member;
        }
      },
      field.member);
}

// Adds every field of `options` to the JSON object `out`.
template <typename Options>
void write_option_fields(nlohmann::json& out, OptionTable<Options> table, const Options& options) {
  for (const OptionField<Options>& field : table)
    out[field.key] = option_value_json(field, options);
}

// "key: value  # unit, range: doc" lines at `indent` spaces; values read back exactly.
template <typename Options>
void print_option_fields(TextBuffer& out, OptionTable<Options> table, const Options& options,
                         int indent) {
  for (const OptionField<Options>& field : table) {
    std::string value, about;
    if (const auto* e = std::get_if<EnumMember<Options>>(&field.member)) {
      value = e->get(options);
      about = e->choices();
    } else if (std::holds_alternative<bool Options::*>(field.member)) {
      value = (options.*std::get<bool Options::*>(field.member)) ? "true" : "false";
      about = "true | false";
    } else {
      const nlohmann::json json = option_value_json(field, options);
      if (json.is_array()) {
        value = fmt::format("[{}, {}, {}]", format_option_number(json[0].get<double>()),
                            format_option_number(json[1].get<double>()),
                            format_option_number(json[2].get<double>()));
      } else {
        value = format_option_number(json.get<double>());
      }
      about = fmt::format("{}, {} to {}", field.unit, format_option_number(field.min),
                          format_option_number(field.max));
    }
    const std::string setting = fmt::format("{:{}}{}: {}", "", indent, field.key, value);
    out.print("{:<44} # {}: {}\n", setting, about, field.doc);
  }
}

}  // namespace odocal::detail
