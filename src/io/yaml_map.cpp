#include "yaml_map.hpp"

#include <fmt/format.h>

#include <cmath>

#include "odocal/options/option_fields.hpp"

namespace odocal::detail {

YAML::Node parse_yaml(const std::string& text, const std::string& file) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError({file, static_cast<std::size_t>(e.mark.line + 1), ""},
                     "not valid YAML: " + e.msg);
  }
}

YamlMap::YamlMap(YAML::Node node, std::string file, std::string path)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {
  if (!node_.IsMap()) throw InputError(location(), "expected a mapping of key: value");
  // yaml-cpp keeps the first of two equal keys and takes [a, b] as a key: both would pass
  // unnoticed.
  std::set<std::string> seen;
  for (const auto& entry : node_) {
    if (!entry.first.IsScalar()) {
      throw InputError({file_, line(entry.first), path_},
                       "a key must be a plain name, not a list or a mapping");
    }
    const std::string key = entry.first.Scalar();
    if (!seen.insert(key).second)
      throw InputError({file_, line(entry.first), key_path(key)}, "key given twice");
  }
}

InputLocation YamlMap::location(const std::string& key) const {
  const YAML::Node value = node_[key];
  return {file_, value.IsDefined() ? line(value) : line(node_), key_path(key)};
}

YAML::Node YamlMap::take(const std::string& key) {
  used_.insert(key);
  return node_[key];
}

void YamlMap::read(const std::string& key, double& value, double min, double max) {
  const YAML::Node node = take(key);
  if (!node.IsDefined()) return;
  double parsed = 0.0;
  try {
    parsed = node.as<double>();
  } catch (const YAML::Exception&) {
    throw InputError(location(key),
                     fmt::format("expected a number, got '{}'",
                                 node.IsScalar() ? node.Scalar() : "<not a scalar>"));
  }
  if (!std::isfinite(parsed) || parsed < min || parsed > max) {
    throw InputError(
        location(key),
        fmt::format("{} is out of range: expected a finite number from {} to {}", node.Scalar(),
                    format_option_number(min), format_option_number(max)));
  }
  value = parsed;
}

void YamlMap::read(const std::string& key, int& value, int min, int max) {
  double parsed = value;
  read(key, parsed, min, max);
  if (parsed != std::round(parsed)) throw InputError(location(key), "expected an integer");
  value = static_cast<int>(parsed);
}

void YamlMap::read(const std::string& key, std::uint64_t& value) {
  const YAML::Node node = take(key);
  if (!node.IsDefined()) return;
  try {
    value = node.as<std::uint64_t>();
  } catch (const YAML::Exception&) {
    throw InputError(location(key), "expected a non-negative integer");
  }
}

void YamlMap::read(const std::string& key, bool& value) {
  const YAML::Node node = take(key);
  if (!node.IsDefined()) return;
  try {
    value = node.as<bool>();
  } catch (const YAML::Exception&) {
    throw InputError(location(key), "expected true or false");
  }
}

void YamlMap::read(const std::string& key, std::string& value) {
  const YAML::Node node = take(key);
  if (!node.IsDefined()) return;
  if (!node.IsScalar()) throw InputError(location(key), "expected a string");
  value = node.Scalar();
}

void YamlMap::read(const std::string& key, Eigen::Vector3d& value, double min, double max) {
  const YAML::Node node = take(key);
  if (!node.IsDefined()) return;
  const std::string expected = fmt::format("expected a list of 3 numbers, each from {} to {}",
                                           format_option_number(min), format_option_number(max));
  if (!node.IsSequence() || node.size() != 3) throw InputError(location(key), expected);
  Eigen::Vector3d parsed;
  for (std::size_t i = 0; i < 3; ++i) {
    try {
      parsed(static_cast<Eigen::Index>(i)) = node[i].as<double>();
    } catch (const YAML::Exception&) {
      throw InputError(location(key), expected);
    }
    const double element = parsed(static_cast<Eigen::Index>(i));
    if (!(element >= min && element <= max)) throw InputError(location(key), expected);
  }
  value = parsed;
}

std::optional<YamlMap> YamlMap::map(const std::string& key) {
  const YAML::Node node = take(key);
  if (!node.IsDefined()) return std::nullopt;
  return YamlMap(node, file_, key_path(key));
}

std::vector<YAML::Node> YamlMap::sequence(const std::string& key) {
  const YAML::Node node = take(key);
  if (!node.IsDefined()) return {};
  if (!node.IsSequence()) throw InputError(location(key), "expected a list");
  return {node.begin(), node.end()};
}

void YamlMap::reject_unknown_keys() const {
  for (const auto& entry : node_) {
    const std::string key = entry.first.Scalar();
    if (used_.count(key) == 0)
      throw InputError({file_, line(entry.first), key_path(key)}, "unknown key");
  }
}

}  // namespace odocal::detail
