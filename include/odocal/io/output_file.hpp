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

// The same for an output written in pieces (a trajectory of any length): nothing appears at
// `path` until commit(); destroyed without it (an error on the way), the temporary file goes.
class OutputFileStream {
 public:
  explicit OutputFileStream(const std::filesystem::path& path);
  ~OutputFileStream();
  OutputFileStream(const OutputFileStream&) = delete;
  OutputFileStream& operator=(const OutputFileStream&) = delete;

  void write(std::string_view contents);  // OutputError on a failed write
  void commit();                          // OutputError when closing or renaming fails

 private:
  [[noreturn]] void abandon();

  std::filesystem::path shown_, target_, temporary_;
  int fd_ = -1;
  int error_ = 0;
  unsigned mode_ = 0;
  bool replaced_ = false, committed_ = false;
};

}  // namespace odocal
