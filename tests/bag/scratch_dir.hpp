#pragma once
// A fresh directory under the system's temporary directory, removed with everything in it. Its
// name carries the process id: ctest runs each test in a process of its own, two at a time, and
// two tests of one fixture must not share (and remove) each other's files.

#include <unistd.h>

#include <filesystem>
#include <string>

namespace odocal::testing {

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("odocal_bag_test_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace odocal::testing
