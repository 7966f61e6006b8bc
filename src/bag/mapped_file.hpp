#pragma once
// A bag file mapped read-only into memory: bags can be many gigabytes, and the readers walk
// them once, so the operating system pages them in instead of the reader copying them.

#include <cstdint>
#include <filesystem>
#include <span>

namespace odocal::bag {

class MappedFile {
 public:
  // Throws InputError naming the file when it is missing, not a regular file or unreadable.
  explicit MappedFile(const std::filesystem::path& path);
  ~MappedFile();
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  std::span<const std::uint8_t> bytes() const { return {data_, size_}; }

 private:
  const std::uint8_t* data_{};
  std::size_t size_{};
};

}  // namespace odocal::bag
