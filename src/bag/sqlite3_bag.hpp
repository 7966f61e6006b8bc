#pragma once
// The SQLite3 reader on a file: SQLite reads the pages it needs instead of the whole file.

#include <filesystem>

#include "odocal/bag/bag_reader.hpp"

namespace odocal::bag {

void read_sqlite3_bag_file(const std::filesystem::path& path, BagVisitor& visitor);

}  // namespace odocal::bag
