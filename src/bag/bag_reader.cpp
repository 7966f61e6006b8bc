#include "odocal/bag/bag_reader.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <map>
#include <optional>

#include "mapped_file.hpp"
#include "odocal/error.hpp"
#include "sqlite3_bag.hpp"

namespace odocal::bag {
namespace {

namespace fs = std::filesystem;

std::optional<BagFormat> format_by_magic(const fs::path& file) {
  std::ifstream stream(file, std::ios::binary);
  std::array<char, 16> head{};
  stream.read(head.data(), head.size());
  const std::string_view text(head.data(), static_cast<std::size_t>(stream.gcount()));
  if (text.starts_with("#ROSBAG V")) return BagFormat::kRos1;
  if (text.starts_with("\x89MCAP")) return BagFormat::kMcap;
  if (text.starts_with("SQLite format 3")) return BagFormat::kSqlite3;
  return std::nullopt;
}

BagFormat format_of_file(const fs::path& file) {
  std::error_code error;
  if (!fs::exists(file, error))
    throw InputError({file.string(), 0, ""}, "cannot open: no such file");
  if (!fs::is_regular_file(file, error))
    throw InputError({file.string(), 0, ""}, "not a regular file");
  if (const auto format = format_by_magic(file)) return *format;
  throw InputError({file.string(), 0, ""},
                   "not a bag: neither a ROS 1 bag, an MCAP file nor an SQLite3 database "
                   "(wrong magic bytes)");
}

BagFormat format_of_storage(const std::string& storage, const fs::path& metadata) {
  if (storage == "mcap") return BagFormat::kMcap;
  if (storage == "sqlite3") return BagFormat::kSqlite3;
  throw InputError({metadata.string(), 0, "storage_identifier"},
                   fmt::format("unknown storage '{}' (odocal reads mcap and sqlite3)", storage));
}

BagFileSet from_metadata(const fs::path& directory, const fs::path& metadata) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(metadata.string());
  } catch (const YAML::Exception& e) {
    throw InputError({metadata.string(), static_cast<std::size_t>(e.mark.line + 1), ""}, e.msg);
  }
  const YAML::Node info = root["rosbag2_bagfile_information"];
  if (!info.IsMap())
    throw InputError({metadata.string(), 0, ""}, "no rosbag2_bagfile_information section");
  try {
    const std::string compression =
        info["compression_mode"] ? info["compression_mode"].as<std::string>() : "";
    if (!compression.empty() && compression != "NONE") {
      throw InputError({metadata.string(), 0, "compression_mode"},
                       fmt::format("compressed bag files ({} mode) are not read; convert with "
                                   "`ros2 bag convert` to uncompressed or chunk-compressed MCAP",
                                   compression));
    }
    BagFileSet set;
    set.format = format_of_storage(info["storage_identifier"].as<std::string>(), metadata);
    for (const YAML::Node& file : info["relative_file_paths"])
      set.files.push_back(directory / file.as<std::string>());
    if (set.files.empty())
      throw InputError({metadata.string(), 0, "relative_file_paths"}, "lists no files");
    return set;
  } catch (const YAML::Exception& e) {
    throw InputError({metadata.string(), static_cast<std::size_t>(e.mark.line + 1), ""}, e.msg);
  }
}

BagFileSet from_directory(const fs::path& directory) {
  const fs::path metadata = directory / "metadata.yaml";
  if (fs::exists(metadata)) return from_metadata(directory, metadata);
  BagFileSet set;
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(directory)) {
    const std::string extension = entry.path().extension().string();
    if (entry.is_regular_file() &&
        (extension == ".bag" || extension == ".mcap" || extension == ".db3"))
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    const BagFormat format = format_of_file(file);
    if (!set.files.empty() && format != set.format) {
      throw InputError({directory.string(), 0, ""},
                       "holds bag files of different formats; name one file");
    }
    set.format = format;
    set.files.push_back(file);
  }
  if (set.files.empty())
    throw InputError({directory.string(), 0, ""},
                     "no metadata.yaml and no .bag, .mcap or .db3 file in the directory");
  return set;
}

// Split files number their topics on their own; the bag's topics are unique by name.
class TopicMerger : public BagVisitor {
 public:
  explicit TopicMerger(BagVisitor& out) : out_(out) {}

  void start_file() { local_.clear(); }

  void topic(std::size_t index, const BagTopic& topic) override {
    auto [it, added] = global_.try_emplace(topic.name, global_.size());
    if (added) out_.topic(it->second, topic);
    if (local_.size() <= index) local_.resize(index + 1);
    local_[index] = it->second;
  }

  void message(const BagMessage& message) override {
    BagMessage global = message;
    global.topic = local_.at(message.topic);
    out_.message(global);
  }

 private:
  BagVisitor& out_;
  std::map<std::string, std::size_t, std::less<>> global_;
  std::vector<std::size_t> local_;
};

}  // namespace

const char* bag_format_name(BagFormat format) {
  switch (format) {
    case BagFormat::kRos1:
      return "ROS 1 bag";
    case BagFormat::kMcap:
      return "MCAP";
    case BagFormat::kSqlite3:
      return "SQLite3";
  }
  return "?";
}

BagFileSet locate_bag(const fs::path& path) {
  std::error_code error;
  if (fs::is_directory(path, error)) return from_directory(path);
  return {format_of_file(path), {path}};
}

void read_bag(const fs::path& path, BagVisitor& visitor) {
  const BagFileSet set = locate_bag(path);
  TopicMerger merger(visitor);
  for (const fs::path& file : set.files) {
    merger.start_file();
    if (set.format == BagFormat::kSqlite3) {
      format_of_file(file);  // the same checks as the mapped formats
      read_sqlite3_bag_file(file, merger);
      continue;
    }
    const MappedFile mapped(file);
    if (set.format == BagFormat::kRos1) {
      read_ros1_bag(mapped.bytes(), file.string(), merger);
    } else {
      read_mcap(mapped.bytes(), file.string(), merger);
    }
  }
}

}  // namespace odocal::bag
