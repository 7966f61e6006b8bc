#pragma once
// JSON result files of the experiments; I/O and parse failures are odocal::Error naming the file.

#include <filesystem>
#include <nlohmann/json.hpp>

namespace odocal::experiments {

void write_json_file(const std::filesystem::path& path, const nlohmann::json& value);
nlohmann::json read_json_file(const std::filesystem::path& path);

}  // namespace odocal::experiments
