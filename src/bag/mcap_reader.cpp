// MCAP (https://mcap.dev/spec): the magic "\x89MCAP0\r\n", then records of <opcode u8><length
// u64><content> up to the footer and the magic again. Messages stand alone or inside chunks
// (stored, zstd or lz4, with a CRC-32 of their records); schemas carry the message definitions
// and channels the topics. The data section is read start to end, so a file without summary or
// index reads as well as one with them.

#include <fmt/format.h>
#include <zlib.h>

#include <map>
#include <string>

#include "byte_cursor.hpp"
#include "decompression.hpp"
#include "odocal/bag/bag_reader.hpp"

namespace odocal::bag {
namespace {

constexpr std::uint8_t kMagic[] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

enum Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kDataEnd = 0x0f,
};

std::string_view read_string(ByteCursor& cursor, std::string_view what) {
  const auto length = cursor.read<std::uint32_t>(what);
  return cursor.take_text(length, what);
}

struct Schema {
  std::string name;
  std::string encoding;  // "ros1msg", "ros2msg", ...
  std::string data;
};

class McapReader {
 public:
  McapReader(std::span<const std::uint8_t> bytes, const std::string& name, BagVisitor& visitor)
      : bytes_(bytes), origin_{name, 0, {}}, visitor_(visitor) {}

  void read() {
    ByteCursor cursor(bytes_, origin_);
    const auto magic = cursor.take(std::min(sizeof(kMagic), cursor.remaining()), "magic");
    if (magic.size() != sizeof(kMagic) || !std::equal(magic.begin(), magic.end(), kMagic))
      throw_bag_error(origin_, 0, "not an MCAP file (no MCAP magic at the start)");
    bool header_seen = false;
    bool data_ended = false;
    while (true) {
      if (cursor.at_end()) cursor.fail("truncated: the file ends before the MCAP footer");
      const std::size_t start = cursor.position();
      const auto opcode = cursor.read<std::uint8_t>("record opcode");
      const auto length = cursor.read<std::uint64_t>("record length");
      const auto content = cursor.take(length, fmt::format("record 0x{:02x}", opcode));
      if (!header_seen && opcode != kHeader) cursor.fail("the first record is not the header");
      header_seen = true;
      if (opcode == kFooter) break;
      // The summary after the data section repeats schemas and channels already read.
      if (opcode == kDataEnd) data_ended = true;
      if (data_ended) continue;
      if (opcode == kChunk) {
        read_chunk(content, cursor.origin_at(start));
      } else {
        record(opcode, content, cursor.origin_at(start));
      }
    }
    const auto closing = cursor.take(std::min(sizeof(kMagic), cursor.remaining()), "magic");
    if (closing.size() != sizeof(kMagic) || !std::equal(closing.begin(), closing.end(), kMagic))
      cursor.fail("truncated: no MCAP magic after the footer");
  }

 private:
  void read_chunk(std::span<const std::uint8_t> content, const ByteOrigin& origin) {
    ByteCursor chunk(content, origin);
    chunk.skip(16, "chunk start and end times");
    const auto uncompressed_size = chunk.read<std::uint64_t>("chunk uncompressed size");
    const auto crc = chunk.read<std::uint32_t>("chunk CRC");
    const std::string compression(read_string(chunk, "chunk compression"));
    const auto records_length = chunk.read<std::uint64_t>("chunk records length");
    const auto compressed = chunk.take(records_length, "chunk records");
    const ChunkBytes records =
        decompress_chunk(compression, compressed, uncompressed_size, origin, origin.base_offset);
    if (crc != 0) {
      const auto actual = static_cast<std::uint32_t>(
          crc32_z(0, records.bytes.data(), static_cast<z_size_t>(records.bytes.size())));
      if (actual != crc) {
        throw_bag_error(
            origin, origin.base_offset,
            fmt::format("chunk CRC mismatch (stored {:08x}, records give {:08x})", crc, actual));
      }
    }
    const std::string context = fmt::format("chunk at byte {}", origin.base_offset);
    const ByteOrigin inner{origin.file, 0, context};
    ByteCursor cursor(records.bytes, inner);
    while (!cursor.at_end()) {
      const std::size_t start = cursor.position();
      const auto opcode = cursor.read<std::uint8_t>("record opcode");
      const auto length = cursor.read<std::uint64_t>("record length");
      const auto content_bytes = cursor.take(length, fmt::format("record 0x{:02x}", opcode));
      record(opcode, content_bytes, cursor.origin_at(start));
    }
  }

  void record(std::uint8_t opcode, std::span<const std::uint8_t> content,
              const ByteOrigin& origin) {
    ByteCursor cursor(content, origin);
    if (opcode == kSchema) {
      const auto id = cursor.read<std::uint16_t>("schema id");
      Schema schema;
      schema.name = read_string(cursor, "schema name");
      schema.encoding = read_string(cursor, "schema encoding");
      schema.data = read_string(cursor, "schema data");
      if (id == 0) cursor.fail("schema id 0 is reserved");
      schemas_.try_emplace(id, std::move(schema));
    } else if (opcode == kChannel) {
      channel(cursor);
    } else if (opcode == kMessage) {
      const auto channel_id = cursor.read<std::uint16_t>("message channel id");
      cursor.skip(4, "message sequence");
      const auto log_time = cursor.read<std::uint64_t>("message log time");
      cursor.skip(8, "message publish time");
      const auto topic = channels_.find(channel_id);
      if (topic == channels_.end())
        cursor.fail(fmt::format("message on channel {} before its channel record", channel_id));
      if (log_time > static_cast<std::uint64_t>(INT64_MAX))
        cursor.fail(fmt::format("message log time {} ns is out of range", log_time));
      visitor_.message({topic->second, static_cast<std::int64_t>(log_time),
                        cursor.take(cursor.remaining(), "message data")});
    }
    // Other records (indexes, attachments, metadata, statistics) say nothing odocal reads.
  }

  void channel(ByteCursor& cursor) {
    const auto id = cursor.read<std::uint16_t>("channel id");
    const auto schema_id = cursor.read<std::uint16_t>("channel schema id");
    BagTopic topic;
    topic.name = read_string(cursor, "channel topic");
    topic.encoding = read_string(cursor, "channel message encoding");
    if (channels_.contains(id)) return;
    if (schema_id != 0) {
      const auto schema = schemas_.find(schema_id);
      if (schema == schemas_.end())
        cursor.fail(fmt::format("channel {} refers to unknown schema {}", id, schema_id));
      topic.type = schema->second.name;
      topic.definition = schema->second.data;
      topic.definition_format = schema->second.encoding;
    }
    auto [it, added] = topic_index_.try_emplace(topic.name, topic_index_.size());
    if (added) visitor_.topic(it->second, topic);
    channels_[id] = it->second;
  }

  std::span<const std::uint8_t> bytes_;
  ByteOrigin origin_;
  BagVisitor& visitor_;
  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, std::size_t> channels_;
  std::map<std::string, std::size_t, std::less<>> topic_index_;
};

}  // namespace

void read_mcap(std::span<const std::uint8_t> bytes, const std::string& name, BagVisitor& visitor) {
  McapReader(bytes, name, visitor).read();
}

}  // namespace odocal::bag
