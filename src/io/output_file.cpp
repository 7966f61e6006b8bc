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

// A name no other writer (this process or another) uses at the same time.
fs::path temporary_beside(const fs::path& target) {
  static std::atomic<unsigned> counter{0};
  return target.parent_path() /
         fmt::format(".{}.tmp-{}-{}", target.filename().string(), ::getpid(), counter++);
}

}  // namespace

OutputFileStream::OutputFileStream(const fs::path& path) : shown_(path) {
  std::error_code error;
  fs::path target = path;
  if (fs::is_symlink(fs::symlink_status(path, error))) {
    target = fs::weakly_canonical(path, error);
    if (error) fail(path, error.value());
  }
  const fs::file_status status = fs::status(target, error);
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    if (fs::is_directory(status)) fail(path, EISDIR);
    // A device or FIFO cannot be replaced: written in place.
    fd_ = ::open(target.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd_ < 0) fail(path, errno);
    target_ = target;
    return;
  }
  if (target.filename().empty()) fail(path, EISDIR);
  if (target.parent_path().empty()) target = fs::path(".") / target;
  target_ = target;
  temporary_ = temporary_beside(target);
  // A replaced file keeps its permissions; a new one gets the umask's.
  replaced_ = fs::exists(status);
  mode_ = replaced_ ? static_cast<unsigned>(status.permissions()) : 0666;
  fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC,
               static_cast<mode_t>(mode_));
  if (fd_ < 0) fail(path, errno);
}

OutputFileStream::~OutputFileStream() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !temporary_.empty()) ::unlink(temporary_.c_str());
}

void OutputFileStream::write(std::string_view contents) {
  if (error_ == 0) error_ = write_all(fd_, contents);
  if (error_ != 0) abandon();
}

void OutputFileStream::commit() {
  if (replaced_ && error_ == 0 && ::fchmod(fd_, static_cast<mode_t>(mode_)) != 0) error_ = errno;
  if (::close(fd_) != 0 && error_ == 0) error_ = errno;
  fd_ = -1;
  if (error_ == 0 && !temporary_.empty() && ::rename(temporary_.c_str(), target_.c_str()) != 0)
    error_ = errno;
  if (error_ != 0) abandon();
  committed_ = true;
}

void OutputFileStream::abandon() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
  temporary_.clear();
  fail(shown_, error_);
}

void write_output_file(const fs::path& path, std::string_view contents) {
  OutputFileStream out(path);
  out.write(contents);
  out.commit();
}

}  // namespace odocal
