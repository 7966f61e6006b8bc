// write_output_file: an output is complete or absent, never half-written, and a failure names
// the file.

#include "odocal/io/output_file.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <filesystem>

#include "../support/run_cli.hpp"
#include "../support/temp_log_dir.hpp"
#include "odocal/error.hpp"
#include "odocal/io/text_output.hpp"

namespace odocal {
namespace {

namespace fs = std::filesystem;
using testing::read_text_file;
using testing::TempLogDir;

std::size_t entries(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), {}));
}

TEST(OutputFile, WritesAndReplacesWholeLeavingNoTemporary) {
  const TempLogDir dir;
  const std::size_t before = entries(dir.path());
  write_output_file(dir.file("out.txt"), "first\n");
  EXPECT_EQ(read_text_file(dir.file("out.txt")), "first\n");
  write_output_file(dir.file("out.txt"), "second, longer\n");
  EXPECT_EQ(read_text_file(dir.file("out.txt")), "second, longer\n");
  EXPECT_EQ(entries(dir.path()), before + 1);
}

TEST(OutputFile, AReplacedFileKeepsItsPermissions) {
  const TempLogDir dir;
  write_output_file(dir.file("out.txt"), "a");
  fs::permissions(dir.file("out.txt"), fs::perms::owner_read | fs::perms::owner_write);
  write_output_file(dir.file("out.txt"), "b");
  EXPECT_EQ(fs::status(dir.file("out.txt")).permissions(),
            fs::perms::owner_read | fs::perms::owner_write);
}

TEST(OutputFile, FollowsASymbolicLinkAndKeepsIt) {
  const TempLogDir dir;
  write_output_file(dir.file("real.txt"), "old");
  fs::create_symlink(dir.file("real.txt"), dir.file("link.txt"));
  write_output_file(dir.file("link.txt"), "new");
  EXPECT_TRUE(fs::is_symlink(dir.file("link.txt")));
  EXPECT_EQ(read_text_file(dir.file("real.txt")), "new");
}

TEST(OutputFile, AFullDeviceIsAnErrorNamingIt) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  try {
    write_output_file("/dev/full", std::string(100000, 'x'));
    FAIL() << "writing to /dev/full succeeded";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write /dev/full: No space left on device"),
              std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(fs::is_character_file("/dev/full"));  // written in place, never replaced
}

TEST(OutputFile, AMissingDirectoryOrADirectoryTargetIsAnErrorAndChangesNothing) {
  const TempLogDir dir;
  const std::size_t before = entries(dir.path());
  EXPECT_THROW(write_output_file(dir.file("no/such/dir/out.txt"), "x"), OutputError);
  fs::create_directory(dir.file("sub"));
  try {
    write_output_file(dir.file("sub"), "x");
    FAIL();
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("sub: Is a directory"), std::string::npos) << e.what();
  }
  EXPECT_EQ(entries(dir.path()), before + 1);
}

// A file-size limit makes the write fail half-way, as a full disk would (and works for root).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ::getrlimit(RLIMIT_FSIZE, &saved_);
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    ::setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*previous_handler_)(int) = nullptr;
};

TEST(OutputFile, AWriteThatFailsHalfWayLeavesTheOldFileAndNoTemporary) {
  const TempLogDir dir;
  write_output_file(dir.file("out.txt"), "old");
  const std::size_t before = entries(dir.path());
  {
    const FileSizeLimit limit(4096);
    try {
      write_output_file(dir.file("out.txt"), std::string(100000, 'x'));
      FAIL() << "a write over the size limit succeeded";
    } catch (const OutputError& e) {
      EXPECT_NE(
          std::string(e.what()).find("cannot write " + dir.file("out.txt") + ": File too large"),
          std::string::npos)
          << e.what();
    }
  }
  EXPECT_EQ(read_text_file(dir.file("out.txt")), "old");
  EXPECT_EQ(entries(dir.path()), before);
}

TEST(TextOutput, PrintsThroughFmtAndWritesOnce) {
  const TempLogDir dir;
  write_text_file(dir.file("t.csv"), [](TextBuffer& out) {
    out.print("a,b\n");
    out.print("{:.2f},{}\n", 1.0 / 3.0, 7);
  });
  EXPECT_EQ(read_text_file(dir.file("t.csv")), "a,b\n0.33,7\n");
}

}  // namespace
}  // namespace odocal
