#pragma once
// A log directory read a time block at a time (odocal/data/log_source.hpp): each stream's file
// is read in chunks of rows as the blocks ask for them and forgotten behind them, so that a
// command walking a log once holds a few blocks of it, whatever its length. Every row is checked
// as read_log checks it (read_log reads through it), with the same messages.

#include <filesystem>
#include <limits>
#include <memory>

#include "odocal/data/log_source.hpp"
#include "odocal/io/log_reader.hpp"

namespace odocal {

class LogBlockReader final : public LogBlockSource {
 public:
  // Only samples with window_from_s <= t <= window_to_s are read (`--from` / `--to`): the first
  // wheel sample inside starts the odometry chain, as crop_log does.
  explicit LogBlockReader(const std::filesystem::path& directory,
                          const LogReadOptions& options = {},
                          double window_from_s = -std::numeric_limits<double>::infinity(),
                          double window_to_s = std::numeric_limits<double>::infinity());
  ~LogBlockReader() override;
  LogBlockReader(const LogBlockReader&) = delete;
  LogBlockReader& operator=(const LogBlockReader&) = delete;

  const std::string& source() const override;
  const VehicleConfig& vehicle() const override;
  bool has_heading() override;
  bool has_truth() override;
  double first_wheel_time_s() override;
  bool wheels_reach(double t_s) override;
  Log block(double from_s, double to_s) override;
  void keep_back(double seconds) override;
  // Every stream meets the wheels' span (else: "streams must share one clock"); with a window,
  // it holds at least 2 wheel samples and a GNSS fix (crop_log's messages).
  void finish() override;
  // The whole log (read_log), moved out of the reader: use it instead of block(), not after.
  Log read_whole();

 private:
  struct Streams;
  std::unique_ptr<Streams> streams_;
};

}  // namespace odocal
