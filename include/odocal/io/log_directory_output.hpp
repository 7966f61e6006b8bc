#pragma once
// A log directory is written whole or not at all: its files go into a hidden directory beside
// the target, and only when every file is written (and, for an import, the log reads back valid)
// do they take the target's place. A new target is the staged directory renamed (atomic). Into
// an existing directory each file is renamed (each atomic) and the old log's files that the new
// one does not have (a stale imu.csv) are removed; files that are not part of a log are left. On
// failure the target is left as it was and the hidden directory is removed.

#include <filesystem>

namespace odocal {

class LogDirectoryOutput {
 public:
  // Refuses (OutputError) a target that exists and is not a directory.
  explicit LogDirectoryOutput(std::filesystem::path target);
  ~LogDirectoryOutput();
  LogDirectoryOutput(const LogDirectoryOutput&) = delete;
  LogDirectoryOutput& operator=(const LogDirectoryOutput&) = delete;

  // Where to write the files now.
  const std::filesystem::path& staging() const { return staging_; }
  // Moves the staged directory into the target's place.
  void commit();

 private:
  std::filesystem::path target_;
  std::filesystem::path staging_;
  bool committed_ = false;
};

// InputError when `output` is `input` or lies inside it: a log written there could overwrite the
// files it is made from, and the next import would read its own output as input.
void refuse_overlapping_directories(const std::filesystem::path& input,
                                    const std::filesystem::path& output);

}  // namespace odocal
