#include "decompression.hpp"

#include <bzlib.h>
#include <fmt/format.h>
#include <lz4frame.h>
#include <zstd.h>

#include <memory>
#include <string>

namespace odocal::bag {
namespace {

void decompress_bz2(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out,
                    const ByteOrigin& origin, std::uint64_t offset) {
  auto out_size = static_cast<unsigned int>(out.size());
  // bzip2's API takes non-const buffers but does not write the source.
  const int status =
      BZ2_bzBuffToBuffDecompress(reinterpret_cast<char*>(out.data()), &out_size,
                                 const_cast<char*>(reinterpret_cast<const char*>(in.data())),
                                 static_cast<unsigned int>(in.size()), 0, 0);
  if (status != BZ_OK) {
    throw_bag_error(origin, offset,
                    status == BZ_OUTBUFF_FULL
                        ? "bz2 chunk is larger than its stated uncompressed size"
                        : fmt::format("bz2 chunk does not decompress (bzip2 error {})", status));
  }
  if (out_size != out.size()) {
    throw_bag_error(origin, offset,
                    fmt::format("bz2 chunk decompresses to {} bytes, its header says {}", out_size,
                                out.size()));
  }
}

void decompress_lz4(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out,
                    const ByteOrigin& origin, std::uint64_t offset) {
  LZ4F_dctx* raw = nullptr;
  if (LZ4F_isError(LZ4F_createDecompressionContext(&raw, LZ4F_VERSION)))
    throw_bag_error(origin, offset, "cannot create an lz4 decompression context");
  const std::unique_ptr<LZ4F_dctx, decltype(&LZ4F_freeDecompressionContext)> context(
      raw, &LZ4F_freeDecompressionContext);
  std::size_t read = 0;
  std::size_t written = 0;
  while (read < in.size()) {
    std::size_t out_room = out.size() - written;
    std::size_t in_left = in.size() - read;
    const std::size_t hint = LZ4F_decompress(context.get(), out.data() + written, &out_room,
                                             in.data() + read, &in_left, nullptr);
    if (LZ4F_isError(hint)) {
      throw_bag_error(origin, offset,
                      fmt::format("lz4 chunk does not decompress ({})", LZ4F_getErrorName(hint)));
    }
    read += in_left;
    written += out_room;
    if (hint == 0) break;  // end of frame
    if (in_left == 0 && out_room == 0) {
      throw_bag_error(origin, offset, "lz4 chunk is larger than its stated uncompressed size");
    }
  }
  if (written != out.size()) {
    throw_bag_error(
        origin, offset,
        fmt::format("lz4 chunk decompresses to {} bytes, its header says {}", written, out.size()));
  }
}

void decompress_zstd(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out,
                     const ByteOrigin& origin, std::uint64_t offset) {
  const std::size_t written = ZSTD_decompress(out.data(), out.size(), in.data(), in.size());
  if (ZSTD_isError(written)) {
    throw_bag_error(origin, offset,
                    fmt::format("zstd chunk does not decompress ({})", ZSTD_getErrorName(written)));
  }
  if (written != out.size()) {
    throw_bag_error(origin, offset,
                    fmt::format("zstd chunk decompresses to {} bytes, its header says {}", written,
                                out.size()));
  }
}

}  // namespace

ChunkBytes decompress_chunk(std::string_view method, std::span<const std::uint8_t> compressed,
                            std::uint64_t uncompressed_size, const ByteOrigin& origin,
                            std::uint64_t offset) {
  if (uncompressed_size > kMaxChunkBytes) {
    throw_bag_error(origin, offset,
                    fmt::format("chunk of {} bytes uncompressed: larger than the {} odocal reads "
                                "(corrupt size field?)",
                                uncompressed_size, kMaxChunkBytes));
  }
  if (method.empty() || method == "none") {
    if (compressed.size() != uncompressed_size) {
      throw_bag_error(origin, offset,
                      fmt::format("uncompressed chunk holds {} bytes, its header says {}",
                                  compressed.size(), uncompressed_size));
    }
    return {{}, compressed};
  }
  ChunkBytes chunk;
  std::vector<std::uint8_t>& out = chunk.storage;
  out.resize(static_cast<std::size_t>(uncompressed_size));
  if (out.empty() && (method == "bz2" || method == "lz4" || method == "zstd")) {
    return chunk;
  } else if (method == "bz2") {
    decompress_bz2(compressed, out, origin, offset);
  } else if (method == "lz4") {
    decompress_lz4(compressed, out, origin, offset);
  } else if (method == "zstd") {
    decompress_zstd(compressed, out, origin, offset);
  } else {
    throw_bag_error(origin, offset,
                    fmt::format("unknown chunk compression '{}' (odocal reads none, bz2, lz4 "
                                "and zstd)",
                                method));
  }
  chunk.bytes = out;
  return chunk;
}

}  // namespace odocal::bag
