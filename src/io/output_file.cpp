#include "odocal/io/output_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <system_error>

#include "odocal/error.hpp"

namespace odocal {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const fs::path& shown, int error) {
  throw OutputError(
      fmt::format("cannot write {}: {}", shown.string(), std::generic_category().message(error)));
}

// Writes everything or reports the first error (a short write on a full disk is one).
int write_all(int fd, std::string_view contents) {
  while (!contents.empty()) {
    const ssize_t written = ::write(fd, contents.data(), contents.size());
    if (written < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    contents.remove_prefix(static_cast<std::size_t>(written));
  }
  return 0;
}

void write_in_place(const fs::path& target, const fs::path& shown, std::string_view contents) {
  const int fd = ::open(target.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) fail(shown, errno);
  const int error = write_all(fd, contents);
  if (::close(fd) != 0 && error == 0) fail(shown, errno);
  if (error != 0) fail(shown, error);
}

// A name no other writer (this process or another) uses at the same time.
fs::path temporary_beside(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  return target.parent_path() /
         fmt::format(".{}.tmp-{}-{}", target.filename().string(), ::getpid(), counter++);
}

}  // namespace

void write_output_file(const fs::path& path, std::string_view contents) {
  std::error_code error;
  fs::path target = path;
  if (fs::is_symlink(fs::symlink_status(path, error))) {
    target = fs::weakly_canonical(path, error);
    if (error) fail(path, error.value());
  }
  const fs::file_status status = fs::status(target, error);
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    if (fs::is_directory(status)) fail(path, EISDIR);
    write_in_place(target, path, contents);
    return;
  }
  if (target.filename().empty()) fail(path, EISDIR);
  if (target.parent_path().empty()) target = fs::path(".") / target;

  const fs::path temporary = temporary_beside(target);
  // A replaced file keeps its permissions; a new one gets the umask's.
  const mode_t mode = fs::exists(status) ? static_cast<mode_t>(status.permissions()) : 0666;
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, mode);
  if (fd < 0) fail(path, errno);
  int write_error = write_all(fd, contents);
  if (fs::exists(status) && write_error == 0 && ::fchmod(fd, mode) != 0) write_error = errno;
  if (::close(fd) != 0 && write_error == 0) write_error = errno;
  if (write_error == 0 && ::rename(temporary.c_str(), target.c_str()) != 0) write_error = errno;
  if (write_error != 0) {
    ::unlink(temporary.c_str());
    fail(path, write_error);
  }
}

}  // namespace odocal
