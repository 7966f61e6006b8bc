#include "experiments/json_file.hpp"

#include <fstream>

#include "io/text_file_writer.hpp"
#include "odocal/error.hpp"

namespace odocal::experiments {

void write_json_file(const std::filesystem::path& path, const nlohmann::json& value) {
  detail::write_text_file(path, [&](fmt::ostream& out) { out.print("{}\n", value.dump(2)); });
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
