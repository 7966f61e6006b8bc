#include "odocal/estimation/prepared_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

#include "odocal/data/stream_columns.hpp"
#include "odocal/estimation/accelerometer_offset.hpp"
#include "odocal/estimation/drive_forward_offset.hpp"
#include "odocal/estimation/log_window.hpp"
#include "odocal/estimation/road_grade.hpp"
#include "odocal/estimation/standstill.hpp"
#include "odocal/estimation/wheel_gaps.hpp"

namespace odocal {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Only a real standing start is cut (a second or two is harmless), keeping a little of it for
// the filters to settle.
constexpr double kMinStandingStartS = 5.0, kLeadS = 1.0;

bool rate_sensor(const WheelStream& wheels) {
  return wheels.unit_rear == WheelUnit::kRadiansPerSecond ||
         wheels.unit_rear == WheelUnit::kMetresPerSecond;
}

// Adds a standstill to the record, joining it to the last one when a block boundary split it.
void add_standstill(std::vector<Standstill>& standing, Standstill still) {
  if (!standing.empty() && still.start_s <= standing.back().end_s) {
    standing.back().end_s = std::max(standing.back().end_s, still.end_s);
    return;
  }
  standing.push_back(still);
}

}  // namespace

std::pair<std::size_t, std::size_t> core_rows(const PreparedBlock& block,
                                              const std::vector<double>& t_s) {
  const auto first = std::lower_bound(t_s.begin(), t_s.end(), block.core_from_s);
  const auto last = block.last ? t_s.end() : std::lower_bound(first, t_s.end(), block.core_to_s);
  return {static_cast<std::size_t>(first - t_s.begin()),
          static_cast<std::size_t>(last - t_s.begin())};
}

Log core_log(const PreparedBlock& block) {
  const Log& context = block.context;
  const auto rows = [&](const auto& stream) {
    const auto [first, last] = core_rows(block, stream.t_s);
    return stream_rows(stream, first, last);
  };
  const auto optional_rows = [&](const auto& stream) {
    using Stream = std::remove_cvref_t<decltype(*stream)>;
    if (!stream) return std::optional<Stream>{};
    Stream out = rows(*stream);
    return out.t_s.empty() ? std::optional<Stream>{} : std::optional<Stream>(std::move(out));
  };
  Log core;
  core.source = context.source;
  core.vehicle = context.vehicle;
  core.wheels = rows(context.wheels);
  core.gnss = rows(context.gnss);
  core.imu = optional_rows(context.imu);
  core.heading = optional_rows(context.heading);
  core.truth = optional_rows(context.truth);
  if (block.first) start_wheel_chain(core.wheels);
  return core;
}

Log InMemoryLogSource::block(double from_s, double to_s) { return slice_log(log_, from_s, to_s); }

BlockPreparation::BlockPreparation(LogBlockSource& source, const CalibrationOptions& options,
                                   LogPreparation& done, std::optional<double> forward_offset_mps2)
    : source_(source),
      options_(options),
      done_(done),
      nominal_(source.vehicle().nominal_params()),
      drive_measure_(nominal_, source.vehicle().body_geometry()),
      log_start_s_(source.first_wheel_time_s()),
      whole_log_offset_mps2_(forward_offset_mps2) {
  // The first block looks back over a standing start for its standstills (and their bias).
  source_.keep_back(options_.prepare_block_s);
  start_s_ = find_start();
  blocks_.emplace(source_, start_s_, options_.prepare_block_s,
                  std::max(log_start_s_, start_s_ - options_.prepare_block_s));
}

LogBlocks::LogBlocks(LogBlockSource& source, double start_s, double block_s, double first_context_s)
    : source_(source), start_s_(start_s), block_s_(block_s), first_context_s_(first_context_s) {}

std::optional<PreparedBlock> LogBlocks::next() {
  if (finished_) return std::nullopt;
  PreparedBlock block;
  block.first = index_ == 0;
  // Boundaries computed alike on both sides, so that neighbouring blocks meet exactly.
  const auto boundary = [&](std::size_t k) { return start_s_ + static_cast<double>(k) * block_s_; };
  block.core_from_s = boundary(index_);
  block.last = !source_.wheels_reach(boundary(index_ + 2));
  block.core_to_s = block.last ? kInfinity : boundary(index_ + 1);
  const double context_from = block.first ? first_context_s_ : block.core_from_s - kBlockMarginS;
  block.context = source_.block(context_from, block.core_to_s + kBlockMarginS);
  if (block.first) start_wheel_chain(block.context.wheels);
  ++index_;
  finished_ = block.last;
  return block;
}

double BlockPreparation::find_start() {
  if (!options_.start_at_first_motion) return log_start_s_;
  // Windows of a block, each from the last sample of the one before (so that no pair of samples
  // is missed), until the wheels move.
  double from_s = log_start_s_;
  while (true) {
    const Log window = source_.block(from_s, from_s + options_.prepare_block_s);
    const std::optional<double> moving =
        first_motion_s(window.wheels, nominal_, options_.coverage.moving_speed_mps);
    if (moving) {
      if (*moving - log_start_s_ <= kMinStandingStartS) return log_start_s_;
      done_.started_at_s = *moving - kLeadS;
      changed_ = true;
      return *done_.started_at_s;
    }
    // A window that holds only its first sample ends at a gap longer than a block: motion across
    // a gap is no motion, and the start stays where the log starts (asking again from the same
    // sample would never end).
    if (window.wheels.t_s.empty() || !(window.wheels.t_s.back() > from_s) ||
        !source_.wheels_reach(std::nextafter(window.wheels.t_s.back(), kInfinity)))
      return log_start_s_;
    from_s = window.wheels.t_s.back();
  }
}

std::optional<PreparedBlock> BlockPreparation::next() {
  std::optional<PreparedBlock> block = blocks_->next();
  if (block) prepare(*block);
  return block;
}

void BlockPreparation::prepare(PreparedBlock& block) {
  Log& log = block.context;
  if (log.wheels.size() < 2) return;
  // What is recorded belongs to the block's own span (the first block's from the context's start:
  // a standing start is reported although it is not used).
  const double record_from = block.first ? log.wheels.t_s.front() : block.core_from_s;
  const auto own = [&](double t_s) { return t_s >= record_from && t_s < block.core_to_s; };

  const std::vector<Standstill> standing = find_standstills(log, nominal_, options_.standstill);
  for (const Standstill& still : standing) {
    const Standstill clipped{std::max(still.start_s, record_from),
                             std::min(still.end_s, block.core_to_s)};
    if (clipped.end_s > clipped.start_s) add_standstill(done_.standstills, clipped);
  }

  if (options_.remove_wheel_rate_bias && rate_sensor(log.wheels)) {
    if (!standing.empty()) {
      bias_ = wheel_rate_bias(log.wheels, standing);
      done_.wheel_rate_bias_per_block.push_back({block.core_from_s, *bias_});
      WheelRateBias mean;
      for (const LogPreparation::BlockBias& each : done_.wheel_rate_bias_per_block) {
        mean.rl_rev_per_s += each.bias.standing_s * each.bias.rl_rev_per_s;
        mean.rr_rev_per_s += each.bias.standing_s * each.bias.rr_rev_per_s;
        mean.standing_s += each.bias.standing_s;
      }
      mean.rl_rev_per_s /= mean.standing_s;
      mean.rr_rev_per_s /= mean.standing_s;
      done_.wheel_rate_bias = mean;
    }
    if (bias_) {
      remove_wheel_rate_bias(log.wheels, *bias_);
      changed_ = true;
    }
  }

  bool projected = false;
  if (options_.use_gnss_altitude) {
    if (const auto profile = grade_from_gnss_altitude(log, nominal_, options_.grade_window_m)) {
      const auto [first, last] = core_rows(block, log.wheels.t_s);
      const double core_m =
          last > first ? profile->wheel_distance_m[last - 1] - profile->wheel_distance_m[first]
                       : 0.0;
      done_.typical_max_grade =
          std::max(done_.typical_max_grade.value_or(0.0), profile->typical_max_grade());
      grade_distance_m_ += core_m;
      grade_excess_m_ += core_m * profile->length_excess();
      grade_scale_variance_m2_ += core_m * core_m * profile->scale_variance();
      if (grade_distance_m_ > 0.0) {
        done_.length_excess = grade_excess_m_ / grade_distance_m_;
        done_.grade_scale_variance =
            grade_scale_variance_m2_ / (grade_distance_m_ * grade_distance_m_);
      } else {
        done_.length_excess = profile->length_excess();
        done_.grade_scale_variance = profile->scale_variance();
      }
      project_to_horizontal(log, *profile);
      projected = true;
      changed_ = true;
    }
  }

  // After the grade's projection: on a hill with altitude, a stop's reading is the offset alone.
  if (options_.remove_accelerometer_offset && log.imu)
    remove_forward_offset(block, standing, own, projected);

  const double max_gap_s = options_.max_wheel_gap_s > 0.0 ? options_.max_wheel_gap_s
                                                          : default_max_wheel_gap_s(log.wheels);
  const std::vector<WheelGap> gaps = find_wheel_gaps(log.wheels, max_gap_s);
  if (!gaps.empty()) {
    break_chain_at_gaps(log.wheels, gaps);
    changed_ = true;
  }
  for (const WheelGap& gap : gaps) {
    if (own(log.wheels.t_s[gap.sample])) done_.wheel_gaps.push_back(gap);
  }
}

void BlockPreparation::remove_forward_offset(PreparedBlock& block,
                                             const std::vector<Standstill>& standing,
                                             const std::function<bool(double)>& own,
                                             bool projected) {
  Log& log = block.context;
  std::vector<Standstill> own_stops;
  std::copy_if(standing.begin(), standing.end(), std::back_inserter(own_stops),
               [&](const Standstill& still) { return own(still.start_s); });
  const std::vector<StopReading> readings = standing_forward_readings(*log.imu, own_stops);
  done_.forward_readings.insert(done_.forward_readings.end(), readings.begin(), readings.end());
  done_.accelerometer_offset = accelerometer_offset(done_.forward_readings);

  // The drive's own measure, where the stops so far are too few (drive_forward_offset.hpp); once
  // 3 stops measure it, they do for the rest of the log.
  const auto& stops = done_.accelerometer_offset;
  done_.drive_forward_offset.reset();
  if (!stops || stops->stops < kMinStopsForOffset) {
    const double own_from = block.first ? log.wheels.t_s.front() : block.core_from_s;
    drive_measure_.add(log, own_from, block.core_to_s, projected);
    done_.drive_forward_offset = drive_measure_.measure();
  }

  double removed = 0.0;
  if (const auto& drive = done_.drive_forward_offset) {
    if (drive->removed) removed = drive->forward_mps2;
  } else if (stops && stops->removed) {
    removed = stops->forward_mps2;
  }
  if (whole_log_offset_mps2_) removed = *whole_log_offset_mps2_;
  done_.removed_forward_mps2 = removed;
  if (removed != 0.0) {
    remove_accelerometer_offset(*log.imu, removed);
    changed_ = true;
  }
  // What each block removed against what the whole drive says now: a long log's early blocks
  // took the running estimate of their time.
  const auto [imu_first, imu_last] = core_rows(block, log.imu->t_s);
  if (imu_last > imu_first)
    removed_per_block_.push_back({log.imu->t_s[imu_last - 1] - log.imu->t_s[imu_first], removed});
  double weights = 0.0, squares = 0.0;
  for (const auto& [duration_s, each] : removed_per_block_) {
    weights += duration_s;
    squares += duration_s * (each - removed) * (each - removed);
  }
  done_.unevenly_removed_forward_mps2 = weights > 0.0 ? std::sqrt(squares / weights) : 0.0;
}

std::optional<double> whole_log_forward_offset(LogBlockSource& source,
                                               const CalibrationOptions& options) {
  if (!options.remove_accelerometer_offset) return std::nullopt;
  LogPreparation done;
  BlockPreparation blocks(source, options, done);
  while (blocks.next()) {
  }
  source.finish();
  return done.forward_offset_for_every_block();
}

}  // namespace odocal
