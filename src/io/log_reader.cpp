#include "odocal/io/log_reader.hpp"

#include "odocal/io/log_block_reader.hpp"

namespace odocal {

Log read_log(const std::filesystem::path& directory, const LogReadOptions& options) {
  return LogBlockReader(directory, options).read_whole();
}

}  // namespace odocal
