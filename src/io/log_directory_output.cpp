#include "odocal/io/log_directory_output.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <array>
#include <string_view>

#include "odocal/error.hpp"

namespace odocal {
namespace {

namespace fs = std::filesystem;

// Every file a log directory can hold (docs/log-format.md, plus the simulator's truth).
constexpr std::array<std::string_view, 8> kLogFiles = {"vehicle.yaml", "wheels.csv",   "gnss.csv",
                                                       "imu.csv",      "heading.csv",  "truth.csv",
                                                       "truth.yaml",   "scenario.yaml"};

[[noreturn]] void fail(const fs::path& path, const std::error_code& error) {
  throw OutputError(fmt::format("cannot write {}: {}", path.string(), error.message()));
}

fs::path absolute_normal(const fs::path& path) {
  std::error_code error;
  fs::path resolved = fs::weakly_canonical(fs::absolute(path, error), error);
  if (error) resolved = fs::absolute(path).lexically_normal();
  return resolved;
}

bool inside(const fs::path& inner, const fs::path& outer) {
  const auto mismatch = std::mismatch(outer.begin(), outer.end(), inner.begin(), inner.end());
  return mismatch.first == outer.end();
}

}  // namespace

LogDirectoryOutput::LogDirectoryOutput(fs::path target) : target_(absolute_normal(target)) {
  if (target_.filename().empty()) target_ = target_.parent_path();  // "out/"
  std::error_code error;
  const fs::file_status status = fs::status(target_, error);
  if (fs::exists(status) && !fs::is_directory(status))
    fail(target_, std::make_error_code(std::errc::not_a_directory));
  const fs::path parent = target_.parent_path();
  fs::create_directories(parent, error);
  if (error) fail(target_, error);
  std::string name =
      (parent / fmt::format(".{}.odocal-XXXXXX", target_.filename().string())).string();
  if (::mkdtemp(name.data()) == nullptr)
    fail(target_, std::error_code(errno, std::generic_category()));
  staging_ = name;
}

LogDirectoryOutput::~LogDirectoryOutput() {
  std::error_code ignored;
  if (!committed_) fs::remove_all(staging_, ignored);
}

void LogDirectoryOutput::commit() {
  std::error_code error;
  if (!fs::exists(target_, error)) {
    fs::rename(staging_, target_, error);
    if (error) fail(target_, error);
    committed_ = true;
    return;
  }
  for (const std::string_view name : kLogFiles) {
    const fs::path staged = staging_ / name, placed = target_ / name;
    if (fs::exists(staged, error)) {
      fs::rename(staged, placed, error);
      if (error) fail(placed, error);
    } else {
      fs::remove(placed, error);  // stale: the new log has no such stream
      if (error) fail(placed, error);
    }
  }
  committed_ = true;
  fs::remove_all(staging_, error);
}

void refuse_overlapping_directories(const fs::path& input, const fs::path& output) {
  const fs::path in = absolute_normal(input), out = absolute_normal(output);
  if (inside(out, in)) {
    throw InputError({output.string(), 0, ""},
                     fmt::format("the output log directory is the input directory {} or inside "
                                 "it: keep the logger's files apart from the log made from them",
                                 input.string()));
  }
}

}  // namespace odocal
