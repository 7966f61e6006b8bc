#pragma once
// Writes MCAP files for the reader tests in the layouts the shared fixtures lack: messages
// outside chunks, lz4 chunks, no summary, and deliberately broken records. Follows the MCAP
// specification (https://mcap.dev/spec) record by record.

#include <lz4frame.h>
#include <zlib.h>
#include <zstd.h>

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace odocal::testing {

class McapBuilder {
 public:
  McapBuilder() {
    append_magic(out_);
    std::vector<std::uint8_t> content;
    put_string(content, "ros2");
    put_string(content, "odocal test");
    record(out_, 0x01, content);
  }

  void schema(std::uint16_t id, std::string_view name, std::string_view encoding,
              std::string_view data) {
    std::vector<std::uint8_t> content;
    put(content, id);
    put_string(content, name);
    put_string(content, encoding);
    put_string(content, data);
    record(target(), 0x03, content);
  }

  void channel(std::uint16_t id, std::uint16_t schema_id, std::string_view topic,
               std::string_view encoding) {
    std::vector<std::uint8_t> content;
    put(content, id);
    put(content, schema_id);
    put_string(content, topic);
    put_string(content, encoding);
    put<std::uint32_t>(content, 0);  // empty metadata map
    record(target(), 0x04, content);
  }

  void message(std::uint16_t channel_id, std::uint64_t log_time_ns,
               std::span<const std::uint8_t> data) {
    std::vector<std::uint8_t> content;
    put(content, channel_id);
    put<std::uint32_t>(content, 0);
    put(content, log_time_ns);
    put(content, log_time_ns);
    put_bytes(content, data.data(), data.size());
    record(target(), 0x05, content);
  }

  void begin_chunk() { in_chunk_ = true; }

  // compression: "", "lz4" or "zstd" (or any name, to test refusal); crc false writes 0.
  void end_chunk(std::string_view compression, bool crc = true) {
    in_chunk_ = false;
    std::vector<std::uint8_t> compressed = chunk_;
    if (compression == "lz4") {
      compressed.resize(LZ4F_compressFrameBound(chunk_.size(), nullptr));
      compressed.resize(LZ4F_compressFrame(compressed.data(), compressed.size(), chunk_.data(),
                                           chunk_.size(), nullptr));
    } else if (compression == "zstd") {
      compressed.resize(ZSTD_compressBound(chunk_.size()));
      compressed.resize(
          ZSTD_compress(compressed.data(), compressed.size(), chunk_.data(), chunk_.size(), 3));
    }
    std::vector<std::uint8_t> content;
    put<std::uint64_t>(content, 0);
    put<std::uint64_t>(content, 0);
    put<std::uint64_t>(content, chunk_.size());
    put<std::uint32_t>(
        content, crc ? static_cast<std::uint32_t>(crc32_z(0, chunk_.data(), chunk_.size())) : 0);
    put_string(content, compression);
    put<std::uint64_t>(content, compressed.size());
    put_bytes(content, compressed.data(), compressed.size());
    record(out_, 0x06, content);
    chunk_.clear();
  }

  std::vector<std::uint8_t> finish() {
    std::vector<std::uint8_t> data_end;
    put<std::uint32_t>(data_end, 0);
    record(out_, 0x0f, data_end);
    std::vector<std::uint8_t> footer;
    put<std::uint64_t>(footer, 0);
    put<std::uint64_t>(footer, 0);
    put<std::uint32_t>(footer, 0);
    record(out_, 0x02, footer);
    append_magic(out_);
    return out_;
  }

 private:
  std::vector<std::uint8_t>& target() { return in_chunk_ ? chunk_ : out_; }

  // resize + memcpy: GCC 12 warns falsely (-Wstringop-overflow) on vector<uint8_t>::insert.
  static void put_bytes(std::vector<std::uint8_t>& out, const void* data, std::size_t size) {
    const std::size_t old = out.size();
    out.resize(old + size);
    if (size != 0) std::memcpy(out.data() + old, data, size);
  }

  template <class T>
  static void put(std::vector<std::uint8_t>& out, T value) {
    put_bytes(out, &value, sizeof(T));
  }

  static void put_string(std::vector<std::uint8_t>& out, std::string_view text) {
    put(out, static_cast<std::uint32_t>(text.size()));
    put_bytes(out, text.data(), text.size());
  }

  static void record(std::vector<std::uint8_t>& out, std::uint8_t opcode,
                     const std::vector<std::uint8_t>& content) {
    out.push_back(opcode);
    put(out, static_cast<std::uint64_t>(content.size()));
    put_bytes(out, content.data(), content.size());
  }

  static void append_magic(std::vector<std::uint8_t>& out) {
    const std::uint8_t magic[] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
    put_bytes(out, magic, sizeof(magic));
  }

  std::vector<std::uint8_t> out_;
  std::vector<std::uint8_t> chunk_;
  bool in_chunk_{};
};

}  // namespace odocal::testing
