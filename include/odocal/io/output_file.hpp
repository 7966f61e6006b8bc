#pragma once
// Every file odocal writes goes through here, so that an output is either complete or absent:
// the text goes to a temporary file beside the target, which is renamed into place only once
// it has been written and closed without error. A failed write leaves the target as it was.

#include <filesystem>
#include <string_view>

namespace odocal {

// Writes `contents` to `path` atomically (see above). A target that exists but is not a regular
// file (a device such as /dev/stdout, a FIFO) is written in place, since it cannot be replaced.
// A symbolic link is followed: the file it names is replaced, the link stays. Throws OutputError
// naming the path and the system's reason.
void write_output_file(const std::filesystem::path& path, std::string_view contents);

}  // namespace odocal
