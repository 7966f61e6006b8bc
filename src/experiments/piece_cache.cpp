#include "experiments/piece_cache.hpp"

#include <fstream>
#include <iterator>

#include "odocal/io/text_output.hpp"

namespace odocal::experiments {
namespace {
const char* const kStampFile = ".piece-stamp";
}

bool PieceCache::reusable(const std::filesystem::path& piece_dir, const std::string& stamp) const {
  if (fresh_) return false;
  std::ifstream in(piece_dir / kStampFile, std::ios::binary);
  if (!in) return false;
  const std::string stored((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return stored == stamp;
}

void PieceCache::open(const std::filesystem::path& piece_dir) const {
  std::filesystem::create_directories(piece_dir);
  std::filesystem::remove(piece_dir / kStampFile);
}

void PieceCache::mark_done(const std::filesystem::path& piece_dir, const std::string& stamp) const {
  write_text_file(piece_dir / kStampFile, [&](TextBuffer& out) { out.print("{}", stamp); });
}

}  // namespace odocal::experiments
