#pragma once
// A log read a time block at a time, so that a command that walks a log once (dead reckoning,
// the doctor) holds a block of it instead of all of it: the whole log in memory
// (odocal/estimation/prepared_blocks.hpp), or a log directory streamed from its files
// (odocal/io/log_block_reader.hpp). Both hand out the same samples, so that what is computed
// from the blocks does not depend on where they came from.

#include <string>

#include "odocal/data/log.hpp"

namespace odocal {

class LogBlockSource {
 public:
  virtual ~LogBlockSource() = default;

  virtual const std::string& source() const = 0;
  virtual const VehicleConfig& vehicle() const = 0;
  // Whether the log has these streams at all (a block may hold none of their samples).
  virtual bool has_heading() = 0;
  virtual bool has_truth() = 0;
  // The first wheel sample's time (the log's start).
  virtual double first_wheel_time_s() = 0;
  // Whether the wheel stream has a sample at or after t_s (reading ahead that far).
  virtual bool wheels_reach(double t_s) = 0;
  // Every stream's samples with from_s <= t <= to_s. from_s never goes back more than the
  // keep_back time before the largest from_s asked so far, so that what lies before that may be
  // forgotten. A wheel sample keeps its increment (the log's first sample has none).
  virtual Log block(double from_s, double to_s) = 0;
  // From now on, block() may ask for samples this long before the largest from_s so far.
  virtual void keep_back(double seconds) { static_cast<void>(seconds); }
  // Checks that need the whole log read (a stream that never meets the wheels' span is a clock
  // mismatch): called once after the last block.
  virtual void finish() {}
};

}  // namespace odocal
