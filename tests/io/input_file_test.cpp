// read_input_file and the command-line number checks: anything that is not a regular, bounded,
// readable file, and any non-finite or unphysical number, is refused with a message naming it.

#include "odocal/io/input_file.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>

#include "../support/run_cli.hpp"
#include "../support/temp_log_dir.hpp"
#include "odocal/error.hpp"

namespace odocal {
namespace {

namespace fs = std::filesystem;
using testing::run_cli;
using testing::TempLogDir;

std::string input_error(const fs::path& path, std::uintmax_t max_bytes = kMaxInputFileBytes) {
  try {
    read_input_file(path, max_bytes);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(InputFile, ReadsARegularFileWhole) {
  const TempLogDir dir;
  std::ofstream(dir.file("a.txt")) << "line 1\nline 2\n";
  EXPECT_EQ(read_input_file(dir.file("a.txt")), "line 1\nline 2\n");
}

TEST(InputFile, RefusesWhatIsNotARegularBoundedFile) {
  const TempLogDir dir;
  EXPECT_NE(input_error(dir.path()).find("directory"), std::string::npos);
  EXPECT_NE(input_error(dir.file("missing.csv")).find("missing.csv"), std::string::npos);
  EXPECT_NE(input_error("/dev/zero").find("/dev/zero"), std::string::npos);
  const std::string fifo = dir.file("fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(input_error(fifo).find("fifo"), std::string::npos);
  std::ofstream(dir.file("big.txt")) << std::string(2000, 'x');
  EXPECT_NE(input_error(dir.file("big.txt"), 1000).find("big.txt"), std::string::npos);
}

TEST(InputFile, ALoopOfLinksIsAnErrorNotAbsence) {
  const TempLogDir dir;
  fs::create_symlink(dir.file("b"), dir.file("a"));
  fs::create_symlink(dir.file("a"), dir.file("b"));
  EXPECT_THROW(input_exists(dir.file("a")), InputError);
  EXPECT_FALSE(input_exists(dir.file("nothing")));
}

TEST(CommandLineNumbers, NonFiniteAndUnphysicalValuesAreUsageErrors) {
  const TempLogDir dir;
  for (const char* arguments :
       {"simulate --out {} --wear-rl nan", "simulate --out {} --wear-rr 1e9",
        "simulate --out {} --gnss-sigma inf"}) {
    std::string command = arguments;
    command.replace(command.find("{}"), 2, dir.file("log"));
    const auto run = run_cli(command);
    EXPECT_EQ(run.status, 2) << command;
    EXPECT_FALSE(fs::exists(dir.file("log"))) << command;
  }
}

}  // namespace
}  // namespace odocal
