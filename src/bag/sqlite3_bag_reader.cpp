// rosbag2's SQLite3 storage (.db3): a table `topics` (id, name, type, serialization_format, ...),
// `messages` (id, topic_id, timestamp ns, data CDR blob) and, from rosbag2 Iron on,
// `message_definitions` (topic_type, encoding, encoded_message_definition). Read with Debian's
// libsqlite3, read-only.

#include <fmt/format.h>
#include <sqlite3.h>

#include <cstring>
#include <map>
#include <memory>
#include <string>

#include "odocal/bag/bag_reader.hpp"
#include "odocal/error.hpp"
#include "sqlite3_bag.hpp"

namespace odocal::bag {
namespace {

using Statement = std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)>;

class Sqlite3Bag {
 public:
  Sqlite3Bag(sqlite3* db, std::string name) : db_(db), name_(std::move(name)) {}

  void read(BagVisitor& visitor) {
    const std::map<std::string, std::pair<std::string, std::string>> definitions =
        message_definitions();
    std::map<std::int64_t, std::size_t> topic_of_id;
    {
      Statement topics = prepare("SELECT id, name, type, serialization_format FROM topics");
      while (step(topics, "topics")) {
        BagTopic topic;
        topic.name = text(topics, 1);
        topic.type = text(topics, 2);
        topic.encoding = text(topics, 3);
        const auto definition = definitions.find(topic.type);
        if (definition != definitions.end()) {
          topic.definition_format = definition->second.first;
          topic.definition = definition->second.second;
        }
        const std::size_t index = topic_of_id.size();
        if (!topic_of_id.try_emplace(sqlite3_column_int64(topics.get(), 0), index).second)
          fail(fmt::format("table topics: id {} twice", sqlite3_column_int64(topics.get(), 0)));
        visitor.topic(index, topic);
      }
    }
    Statement messages =
        prepare("SELECT id, topic_id, timestamp, data FROM messages ORDER BY timestamp, id");
    while (step(messages, "messages")) {
      const std::int64_t id = sqlite3_column_int64(messages.get(), 0);
      const auto topic = topic_of_id.find(sqlite3_column_int64(messages.get(), 1));
      if (topic == topic_of_id.end()) {
        fail(fmt::format("table messages, id {}: topic_id {} is not in table topics", id,
                         sqlite3_column_int64(messages.get(), 1)));
      }
      const auto* data = static_cast<const std::uint8_t*>(sqlite3_column_blob(messages.get(), 3));
      const auto size = static_cast<std::size_t>(sqlite3_column_bytes(messages.get(), 3));
      visitor.message({topic->second, sqlite3_column_int64(messages.get(), 2), {data, size}});
    }
  }

 private:
  // topic type -> (format, text); empty when the table is absent (rosbag2 before Iron).
  std::map<std::string, std::pair<std::string, std::string>> message_definitions() {
    std::map<std::string, std::pair<std::string, std::string>> out;
    Statement exists =
        prepare("SELECT 1 FROM sqlite_master WHERE type='table' AND name='message_definitions'");
    if (!step(exists, "sqlite_master")) return out;
    Statement rows =
        prepare("SELECT topic_type, encoding, encoded_message_definition FROM message_definitions");
    while (step(rows, "message_definitions")) out[text(rows, 0)] = {text(rows, 1), text(rows, 2)};
    return out;
  }

  Statement prepare(const char* sql) {
    sqlite3_stmt* raw = nullptr;
    if (sqlite3_prepare_v2(db_, sql, -1, &raw, nullptr) != SQLITE_OK) {
      sqlite3_finalize(raw);
      fail(fmt::format("not a rosbag2 database ({})", sqlite3_errmsg(db_)));
    }
    return {raw, &sqlite3_finalize};
  }

  bool step(Statement& statement, const char* table) {
    const int status = sqlite3_step(statement.get());
    if (status == SQLITE_ROW) return true;
    if (status == SQLITE_DONE) return false;
    fail(fmt::format("table {}: {}", table, sqlite3_errmsg(db_)));
  }

  std::string text(Statement& statement, int column) {
    const auto* value = sqlite3_column_text(statement.get(), column);
    if (value == nullptr) return {};
    return {reinterpret_cast<const char*>(value),
            static_cast<std::size_t>(sqlite3_column_bytes(statement.get(), column))};
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError({name_, 0, ""}, problem);
  }

  sqlite3* db_;
  std::string name_;
};

using Database = std::unique_ptr<sqlite3, decltype(&sqlite3_close)>;

Database open_database(const std::string& uri, const std::string& name, int extra_flags) {
  sqlite3* raw = nullptr;
  const int status =
      sqlite3_open_v2(uri.c_str(), &raw, SQLITE_OPEN_READONLY | extra_flags, nullptr);
  Database db(raw, &sqlite3_close);
  if (status != SQLITE_OK) {
    throw InputError({name, 0, ""}, fmt::format("cannot open as SQLite3: {}",
                                                raw ? sqlite3_errmsg(raw) : "out of memory"));
  }
  return db;
}

}  // namespace

void read_sqlite3_bag_file(const std::filesystem::path& path, BagVisitor& visitor) {
  const std::string name = path.string();
  const Database db = open_database(name, name, 0);
  Sqlite3Bag(db.get(), name).read(visitor);
}

void read_sqlite3_bag(std::span<const std::uint8_t> bytes, const std::string& name,
                      BagVisitor& visitor) {
  const Database db = open_database(":memory:", name, 0);
  // sqlite3_deserialize wants a buffer it may own; give it a copy from sqlite3_malloc.
  auto* copy = static_cast<unsigned char*>(sqlite3_malloc64(bytes.size() + 1));
  if (copy == nullptr) throw InputError({name, 0, ""}, "out of memory");
  if (!bytes.empty()) std::memcpy(copy, bytes.data(), bytes.size());
  const int status =
      sqlite3_deserialize(db.get(), "main", copy, static_cast<sqlite3_int64>(bytes.size()),
                          static_cast<sqlite3_int64>(bytes.size() + 1),
                          SQLITE_DESERIALIZE_FREEONCLOSE | SQLITE_DESERIALIZE_READONLY);
  if (status != SQLITE_OK)
    throw InputError({name, 0, ""}, fmt::format("not an SQLite3 file ({})", status));
  Sqlite3Bag(db.get(), name).read(visitor);
}

}  // namespace odocal::bag
