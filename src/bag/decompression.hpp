#pragma once
// Decompression of bag chunks by Debian's libraries: bz2 (libbz2), lz4 frames (liblz4; ROS 1's
// roslz4 and MCAP both write the LZ4 frame format) and zstd (libzstd).

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "byte_cursor.hpp"

namespace odocal::bag {

// Larger chunks than this are refused: writers use a few MB, and a corrupt size field must not
// allocate gigabytes.
inline constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{256} << 20;

// A chunk's records: `bytes` views `storage` when decompressed, the input when stored as is.
struct ChunkBytes {
  std::vector<std::uint8_t> storage;
  std::span<const std::uint8_t> bytes;
};

// `method`: "" or "none", "bz2", "lz4", "zstd". The result must have exactly
// `uncompressed_size` bytes; anything else is an InputError at `offset` of `origin`.
ChunkBytes decompress_chunk(std::string_view method, std::span<const std::uint8_t> compressed,
                            std::uint64_t uncompressed_size, const ByteOrigin& origin,
                            std::uint64_t offset);

}  // namespace odocal::bag
