#pragma once
// A throw-away log directory for reader tests: starts as a small valid log; a test overwrites or
// removes one file to build each malformed case.

#include <filesystem>
#include <string>

namespace odocal::testing {

class TempLogDir {
 public:
  TempLogDir();  // writes the valid baseline log
  ~TempLogDir();
  TempLogDir(const TempLogDir&) = delete;
  TempLogDir& operator=(const TempLogDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  void write(const std::string& name, const std::string& contents) const;
  void remove(const std::string& name) const;

 private:
  std::filesystem::path path_;
};

}  // namespace odocal::testing
