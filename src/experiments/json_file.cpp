#include "experiments/json_file.hpp"

#include <fstream>

#include "odocal/error.hpp"
#include "odocal/io/text_output.hpp"

namespace odocal::experiments {

void write_json_file(const std::filesystem::path& path, const nlohmann::json& value) {
  write_text_file(path, [&](TextBuffer& out) { out.print("{}\n", value.dump(2)); });
}

nlohmann::json read_json_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot read " + path.string());
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path.string() + ": not valid JSON: " + e.what());
  }
}

}  // namespace odocal::experiments
