// ROS 1 bag format 2.0 (http://wiki.ros.org/Bags/Format/2.0): after the line "#ROSBAG V2.0",
// records of <header length u32><header fields><data length u32><data>, each header field
// <length u32>name=value and the record's kind in its "op" field. Messages live in chunks
// (stored, bz2 or lz4); connection records, in chunks and again in the index section at the
// end, carry each topic's type and message definition.

#include <fmt/format.h>

#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "byte_cursor.hpp"
#include "decompression.hpp"
#include "odocal/bag/bag_reader.hpp"

namespace odocal::bag {
namespace {

constexpr std::string_view kMagic = "#ROSBAG V2.0\n";

enum Op : std::uint8_t {
  kMessageData = 0x02,
  kBagHeader = 0x03,
  kIndexData = 0x04,
  kChunk = 0x05,
  kChunkInfo = 0x06,
  kConnection = 0x07,
};

struct Record {
  std::size_t start{};  // position of the record's first byte in its cursor
  std::span<const std::uint8_t> header;
  std::span<const std::uint8_t> data;
};

// A record's header fields (or a connection record's data) by name, viewing the file's bytes.
// Problems are reported at the record's start.
class HeaderFields {
 public:
  HeaderFields(std::span<const std::uint8_t> header, const ByteCursor& where,
               std::size_t record_start)
      : origin_(where.origin_at(record_start)) {
    ByteCursor fields(header, origin_);
    while (!fields.at_end()) {
      const auto length = fields.read<std::uint32_t>("header field length");
      const std::string_view field = fields.take_text(length, "header field");
      const auto equals = field.find('=');
      if (equals == std::string_view::npos) fields.fail("header field without '='");
      values_[field.substr(0, equals)] = field.substr(equals + 1);
    }
  }

  std::optional<std::string_view> find(std::string_view name) const {
    const auto it = values_.find(name);
    if (it == values_.end()) return std::nullopt;
    return it->second;
  }

  std::string_view text(std::string_view name) const {
    const auto value = find(name);
    if (!value) fail(fmt::format("record has no '{}' field", name));
    return *value;
  }

  template <class T>
  T number(std::string_view name) const {
    const std::string_view value = text(name);
    if (value.size() != sizeof(T)) {
      fail(fmt::format("field '{}' has {} bytes, expected {}", name, value.size(), sizeof(T)));
    }
    T out;
    std::memcpy(&out, value.data(), sizeof(T));
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw_bag_error(origin_, origin_.base_offset, "record: " + problem);
  }

  std::map<std::string_view, std::string_view, std::less<>> values_;
  ByteOrigin origin_;
};

Record next_record(ByteCursor& cursor) {
  Record record;
  record.start = cursor.position();
  const auto header_length = cursor.read<std::uint32_t>("record header length");
  record.header = cursor.take(header_length, "record header");
  const auto data_length = cursor.read<std::uint32_t>("record data length");
  record.data = cursor.take(data_length, "record data");
  return record;
}

class Ros1BagReader {
 public:
  Ros1BagReader(std::span<const std::uint8_t> bytes, const std::string& name, BagVisitor& visitor)
      : bytes_(bytes), origin_{name, 0, {}}, visitor_(visitor) {}

  void read() {
    ByteCursor cursor(bytes_, origin_);
    const std::string_view magic =
        cursor.take_text(std::min<std::size_t>(kMagic.size(), cursor.remaining()), "magic");
    if (magic != kMagic) {
      throw_bag_error(origin_, 0,
                      magic.starts_with("#ROSBAG V")
                          ? "ROS bag of a format other than 2.0 (odocal reads format 2.0)"
                          : "not a ROS 1 bag (no '#ROSBAG V2.0' line at the start)");
    }
    const Record bag_header = next_record(cursor);
    const HeaderFields header(bag_header.header, cursor, bag_header.start);
    if (header.number<std::uint8_t>("op") != kBagHeader)
      cursor.fail("the first record is not the bag header");
    const auto index_position = header.number<std::uint64_t>("index_pos");
    // A bag whose recording was cut off has index_pos 0: its chunks are read without the index.
    std::size_t data_end = bytes_.size();
    if (index_position != 0) {
      if (index_position < cursor.position() || index_position > bytes_.size())
        cursor.fail(fmt::format("index position {} lies outside the file", index_position));
      data_end = static_cast<std::size_t>(index_position);
      read_index_connections(static_cast<std::size_t>(index_position));
    }
    while (cursor.position() < data_end) {
      const Record record = next_record(cursor);
      const HeaderFields fields(record.header, cursor, record.start);
      const auto op = fields.number<std::uint8_t>("op");
      if (op == kChunk) {
        read_chunk(record, fields);
      } else if (op == kConnection) {
        connection(record, fields, cursor);
      } else if (op == kMessageData) {
        message(record, fields, cursor);
      } else if (op != kIndexData && op != kChunkInfo) {
        cursor.fail(fmt::format("unknown record op 0x{:02x}", op));
      }
    }
  }

 private:
  void read_index_connections(std::size_t index_position) {
    ByteCursor index(bytes_, origin_);
    index.seek(index_position, "index position");
    while (!index.at_end()) {
      const Record record = next_record(index);
      const HeaderFields fields(record.header, index, record.start);
      if (fields.number<std::uint8_t>("op") == kConnection) connection(record, fields, index);
    }
  }

  void read_chunk(const Record& record, const HeaderFields& fields) {
    const auto size = fields.number<std::uint32_t>("size");
    const std::string compression(fields.text("compression"));
    const ChunkBytes chunk =
        decompress_chunk(compression, record.data, size, origin_, record.start);
    const std::string context = fmt::format("chunk at byte {}", record.start);
    const ByteOrigin chunk_origin{origin_.file, 0, context};
    ByteCursor cursor(chunk.bytes, chunk_origin);
    while (!cursor.at_end()) {
      const Record inner = next_record(cursor);
      const HeaderFields inner_fields(inner.header, cursor, inner.start);
      const auto op = inner_fields.number<std::uint8_t>("op");
      if (op == kConnection) {
        connection(inner, inner_fields, cursor);
      } else if (op == kMessageData) {
        message(inner, inner_fields, cursor);
      } else {
        cursor.fail(fmt::format("record op 0x{:02x} inside a chunk", op));
      }
    }
  }

  void connection(const Record& record, const HeaderFields& fields, ByteCursor& where) {
    const auto id = fields.number<std::uint32_t>("conn");
    if (topics_.contains(id)) return;  // every connection is written twice
    const HeaderFields details(record.data, where, record.start);
    BagTopic topic;
    topic.name = std::string(fields.text("topic"));
    topic.type = std::string(details.text("type"));
    topic.encoding = "ros1";
    topic.definition = std::string(details.find("message_definition").value_or(""));
    topic.definition_format = topic.definition.empty() ? "" : "ros1msg";
    // Several connections (publishers) on one topic are one topic.
    auto [it, added] = topic_index_.try_emplace(topic.name, topic_index_.size());
    if (added) visitor_.topic(it->second, topic);
    topics_[id] = it->second;
  }

  void message(const Record& record, const HeaderFields& fields, ByteCursor& where) {
    const auto id = fields.number<std::uint32_t>("conn");
    const auto topic = topics_.find(id);
    if (topic == topics_.end())
      throw_bag_error(where.origin_at(record.start), where.origin_at(record.start).base_offset,
                      fmt::format("message on connection {} before its connection record", id));
    const auto time = fields.number<std::uint64_t>("time");
    const auto seconds = static_cast<std::int64_t>(time & 0xffffffffu);
    const auto nanoseconds = static_cast<std::int64_t>(time >> 32);
    visitor_.message({topic->second, seconds * 1'000'000'000 + nanoseconds, record.data});
  }

  std::span<const std::uint8_t> bytes_;
  ByteOrigin origin_;
  BagVisitor& visitor_;
  std::map<std::uint32_t, std::size_t> topics_;
  std::map<std::string, std::size_t, std::less<>> topic_index_;
};

}  // namespace

void read_ros1_bag(std::span<const std::uint8_t> bytes, const std::string& name,
                   BagVisitor& visitor) {
  Ros1BagReader(bytes, name, visitor).read();
}

}  // namespace odocal::bag
