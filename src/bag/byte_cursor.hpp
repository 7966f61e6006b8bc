#pragma once
// Bounds-checked little-endian reading of a binary container (ROS 1 bag records, MCAP records,
// CDR and ROS 1 message payloads). Every read past the end is an InputError naming the file and
// the byte offset, never an out-of-bounds access.

#include <bit>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

#include "odocal/error.hpp"

namespace odocal::bag {

// Where bytes came from, for error messages: the file and the offset of the bytes' first byte
// in it (for a decompressed chunk: the chunk's offset, and "in chunk" in the message).
struct ByteOrigin {
  std::string file;
  std::uint64_t base_offset{};
  std::string_view context;  // e.g. "chunk at byte 4117", empty at the top level
};

[[noreturn]] void throw_bag_error(const ByteOrigin& origin, std::uint64_t offset,
                                  const std::string& problem);

class ByteCursor {
 public:
  ByteCursor(std::span<const std::uint8_t> bytes, const ByteOrigin& origin)
      : bytes_(bytes), origin_(&origin) {}

  std::size_t position() const { return position_; }
  std::size_t remaining() const { return bytes_.size() - position_; }
  bool at_end() const { return position_ == bytes_.size(); }
  // Offset of the current position in the file (or chunk), for messages.
  std::uint64_t offset() const { return origin_->base_offset + position_; }

  template <class T>
  T read(std::string_view what) {
    static_assert(std::is_arithmetic_v<T>);
    require(sizeof(T), what);
    T value;
    std::memcpy(&value, bytes_.data() + position_, sizeof(T));
    position_ += sizeof(T);
    return value;
  }

  std::span<const std::uint8_t> take(std::uint64_t count, std::string_view what) {
    require(count, what);
    const auto out = bytes_.subspan(position_, static_cast<std::size_t>(count));
    position_ += static_cast<std::size_t>(count);
    return out;
  }

  std::string_view take_text(std::uint64_t count, std::string_view what) {
    const auto bytes = take(count, what);
    return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
  }

  void skip(std::uint64_t count, std::string_view what) { take(count, what); }

  // Moves to `position` (bytes from the start of this cursor's span).
  void seek(std::uint64_t position, std::string_view what) {
    if (position > bytes_.size())
      fail(std::string(what) + " points past the end of the data (truncated file?)");
    position_ = static_cast<std::size_t>(position);
  }

  // The origin of bytes that start at `position` of this cursor (a record inside it).
  ByteOrigin origin_at(std::size_t position) const {
    return {origin_->file, origin_->base_offset + position, origin_->context};
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw_bag_error(*origin_, offset(), problem);
  }

 private:
  void require(std::uint64_t count, std::string_view what) const {
    if (count > remaining()) {
      fail("truncated: " + std::string(what) + " needs " + std::to_string(count) + " bytes, only " +
           std::to_string(remaining()) + " left");
    }
  }

  std::span<const std::uint8_t> bytes_;
  const ByteOrigin* origin_;
  std::size_t position_{};
};

static_assert(std::endian::native == std::endian::little,
              "the bag readers read little-endian fields by copying bytes");

}  // namespace odocal::bag
