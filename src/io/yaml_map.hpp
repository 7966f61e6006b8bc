#pragma once
// Strict reading of a YAML mapping: typed values with range checks, and an error for every key
// nobody asked for. Every error names file, line and the full key path.

#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <optional>
#include <set>
#include <string>

#include "odocal/error.hpp"

namespace odocal::detail {

class YamlMap {
 public:
  // `path` is the dotted key path of `node` for messages ("" for the document root).
  YamlMap(YAML::Node node, std::string file, std::string path);

  bool has(const std::string& key) const { return node_[key].IsDefined(); }
  // Each reader leaves `value` unchanged when the key is absent.
  void read(const std::string& key, double& value, double min, double max);
  void read(const std::string& key, int& value, int min, int max);
  void read(const std::string& key, std::uint64_t& value);
  void read(const std::string& key, bool& value);
  void read(const std::string& key, std::string& value);
  // A list of 3 numbers, each from min to max.
  void read(const std::string& key, Eigen::Vector3d& value, double min, double max);
  std::optional<YamlMap> map(const std::string& key);
  // The sequence under `key` (empty when absent); throws when it is not a sequence.
  std::vector<YAML::Node> sequence(const std::string& key);
  // Throws for any key not read.
  void reject_unknown_keys() const;

  InputLocation location(const std::string& key) const;
  InputLocation location() const { return {file_, line(node_), path_}; }
  const std::string& file() const { return file_; }
  std::string key_path(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }

 private:
  static std::size_t line(const YAML::Node& node) {
    return static_cast<std::size_t>(node.Mark().line + 1);
  }
  YAML::Node take(const std::string& key);

  YAML::Node node_;
  std::string file_;
  std::string path_;
  std::set<std::string> used_;
};

// Parses `text` (labelled `file` in messages) as YAML; throws InputError on syntax errors.
YAML::Node parse_yaml(const std::string& text, const std::string& file);

}  // namespace odocal::detail
