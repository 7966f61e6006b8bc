#pragma once
// Finished pieces of an experiment stay on disk, each in its own directory with a stamp of the
// configuration that produced it. A re-run reuses a piece whose stamp matches, unless it was asked
// to start afresh; a changed configuration recomputes the piece.

#include <filesystem>
#include <string>

namespace odocal::experiments {

class PieceCache {
 public:
  explicit PieceCache(bool fresh) : fresh_(fresh) {}

  bool reusable(const std::filesystem::path& piece_dir, const std::string& stamp) const;
  // Creates the directory (the piece writes into it), removing a stale stamp.
  void open(const std::filesystem::path& piece_dir) const;
  // Call after every file of the piece is written.
  void mark_done(const std::filesystem::path& piece_dir, const std::string& stamp) const;

 private:
  bool fresh_;
};

}  // namespace odocal::experiments
