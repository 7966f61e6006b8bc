#pragma once
// A log prepared a block at a time (log_preparation.hpp says what preparing does), so that a
// command walking a long log holds one block of it: from its start, blocks of
// prepare_block_s (10 minutes) of the log's clock, each prepared on itself and a margin of
// kBlockMarginS either side (its standstills, their wheel-rate bias, the road grade, the wheel
// gaps). The last block takes the rest (one to two blocks long), so a log shorter than two
// blocks is prepared whole. A block without a standstill keeps the previous block's bias: a
// sensor's bias drifts with temperature over hours, and each block measures its own.

#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "odocal/data/log_source.hpp"
#include "odocal/estimation/calibration_options.hpp"
#include "odocal/estimation/drive_forward_offset.hpp"
#include "odocal/estimation/log_preparation.hpp"

namespace odocal {

inline constexpr double kBlockMarginS = 60.0;

struct PreparedBlock {
  Log context;  // the block with its margins, prepared
  // Its own samples: core_from_s <= t < core_to_s; the last block's to the end (+inf).
  double core_from_s{};
  double core_to_s{};
  bool first{};
  bool last{};
};

// The rows [first, last) of a stream of the block (time base t_s) inside its own span.
std::pair<std::size_t, std::size_t> core_rows(const PreparedBlock& block,
                                              const std::vector<double>& t_s);
// The block's own span as a log of its own samples (the first block's first wheel sample
// starts the chain).
Log core_log(const PreparedBlock& block);

// The whole log in memory as a block source.
class InMemoryLogSource final : public LogBlockSource {
 public:
  explicit InMemoryLogSource(const Log& log) : log_(log) {}
  const std::string& source() const override { return log_.source; }
  const VehicleConfig& vehicle() const override { return log_.vehicle; }
  bool has_heading() override { return log_.heading.has_value(); }
  bool has_truth() override { return log_.truth.has_value(); }
  double first_wheel_time_s() override { return log_.wheels.t_s.front(); }
  bool wheels_reach(double t_s) override { return log_.wheels.t_s.back() >= t_s; }
  Log block(double from_s, double to_s) override;

 private:
  const Log& log_;
};

// The blocks of a log as they come (not prepared): from start_s, blocks of block_s, each with
// its margins; the first block's context reaches back to first_context_s.
class LogBlocks {
 public:
  LogBlocks(LogBlockSource& source, double start_s, double block_s, double first_context_s);
  std::optional<PreparedBlock> next();

 private:
  LogBlockSource& source_;
  double start_s_, block_s_, first_context_s_;
  std::size_t index_{};
  bool finished_{};
};

class BlockPreparation {
 public:
  // Finds where the log is used from (its first motion, options.start_at_first_motion) and
  // records it in `done`, which collects what every block finds. `forward_offset_mps2`: the
  // accelerometer's forward offset that a pass over the whole log removed at its end
  // (whole_log_forward_offset), removed from every block in place of the running estimate.
  BlockPreparation(LogBlockSource& source, const CalibrationOptions& options, LogPreparation& done,
                   std::optional<double> forward_offset_mps2 = std::nullopt);

  // The next block, prepared; nothing after the last.
  std::optional<PreparedBlock> next();
  // Whether preparing changed anything so far (a start cut, a bias removed, hills projected, a
  // gap broken): if not, the prepared log is the log itself.
  bool changed() const { return changed_; }

 private:
  double find_start();
  void prepare(PreparedBlock& block);
  // The accelerometer's forward offset: the stops' readings, or the drive's, and its removal.
  void remove_forward_offset(PreparedBlock& block, const std::vector<Standstill>& standing,
                             const std::function<bool(double)>& own, bool projected);

  LogBlockSource& source_;
  CalibrationOptions options_;  // a copy: a temporary may be passed
  LogPreparation& done_;
  OdometryParams nominal_;
  DriveForwardMeasure drive_measure_;
  double log_start_s_{}, start_s_{};
  std::optional<LogBlocks> blocks_;
  bool changed_{};
  std::optional<WheelRateBias> bias_;  // the last block's, for blocks without a standstill
  double grade_distance_m_{}, grade_excess_m_{}, grade_scale_variance_m2_{};
  std::vector<std::pair<double, double>> removed_per_block_;  // IMU time s, removed m/s^2
  std::optional<double> whole_log_offset_mps2_;
};

// What a long log's last block removes as the accelerometer's forward offset, where its blocks
// removed it unevenly (each the running estimate of its time): a pass over the whole source,
// prepared as BlockPreparation prepares it, for a second pass to remove from every block.
// Nothing where every block removed the same.
std::optional<double> whole_log_forward_offset(LogBlockSource& source,
                                               const CalibrationOptions& options);

}  // namespace odocal
