#include "diagnosis_facts.hpp"

#include <algorithm>
#include <cmath>

#include "odocal/estimation/calibration_options.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/median.hpp"
#include "odocal/estimation/prepared_blocks.hpp"
#include "odocal/estimation/road_grade.hpp"

namespace odocal::detail {
namespace {

void add_span(StreamSpan& span, const std::vector<double>& t_s, std::size_t first,
              std::size_t last) {
  if (first >= last) return;
  if (span.samples == 0) span.first_s = t_s[first];
  span.last_s = t_s[last - 1];
  span.samples += last - first;
}

bool rate_sensor(WheelUnit unit) {
  return unit == WheelUnit::kRadiansPerSecond || unit == WheelUnit::kMetresPerSecond;
}

class FactGathering {
 public:
  FactGathering(LogBlockSource& source, DiagnosisSignals& signals, double step_s)
      : source_(source), signals_(signals), step_s_(step_s) {
    facts_.vehicle = source.vehicle();
    nominal_ = facts_.vehicle.nominal_params();
    drive_.emplace(nominal_, facts_.vehicle.body_geometry());
    signals_ = DiagnosisSignals{};
    signals_.step_s = step_s;
  }

  DiagnosisFacts run() {
    const double start_s = source_.first_wheel_time_s();
    LogBlocks blocks(source_, start_s, CalibrationOptions{}.prepare_block_s, start_s);
    while (const std::optional<PreparedBlock> block = blocks.next()) add(*block);
    source_.finish();
    facts_.drive_forward_offset = drive_->measure();
    // The grid of a log whose wheels and GNSS share a few seconds only is no comparison.
    const double shared_s =
        std::min(facts_.wheels.last_s, facts_.gnss.last_s) - grid_from_.value_or(0.0);
    if (!grid_from_ || !(shared_s > 5.0)) {
      signals_ = DiagnosisSignals{};
      signals_.step_s = step_s_;
    }
    if (bias_standing_s_ > 0.0) {
      facts_.wheel_rate_bias =
          WheelRateBias{bias_sum_.rl_rev_per_s / bias_standing_s_,
                        bias_sum_.rr_rev_per_s / bias_standing_s_, bias_standing_s_};
    }
    return std::move(facts_);
  }

 private:
  void add(const PreparedBlock& block) {
    const Log& log = block.context;
    const auto rows = [&](const std::vector<double>& t_s) { return core_rows(block, t_s); };
    const auto [wheel_first, wheel_last] = rows(log.wheels.t_s);
    add_span(facts_.wheels, log.wheels.t_s, wheel_first, wheel_last);
    if (!log.wheels.t_s.empty()) facts_.wheel_unit = log.wheels.unit_rear;
    const auto [gnss_first, gnss_last] = rows(log.gnss.t_s);
    add_span(facts_.gnss, log.gnss.t_s, gnss_first, gnss_last);
    facts_.gnss_geodetic = facts_.gnss_geodetic || log.gnss.origin.has_value();
    facts_.gnss_altitude = facts_.gnss_altitude || !log.gnss.altitude_m.empty();
    if (log.imu) {
      const auto [first, last] = rows(log.imu->t_s);
      add_span(facts_.imu, log.imu->t_s, first, last);
    }
    if (log.heading) {
      const auto [first, last] = rows(log.heading->t_s);
      add_span(facts_.heading, log.heading->t_s, first, last);
    }
    add_repeats(log.gnss, gnss_first, gnss_last);
    add_gnss_gaps(log.gnss, gnss_first, gnss_last);
    if (log.wheels.size() >= 2) {
      for (const WheelGap& gap : find_wheel_gaps(log.wheels, default_max_wheel_gap_s(log.wheels))) {
        if (gap.sample >= wheel_first && gap.sample < wheel_last) facts_.wheel_gaps.push_back(gap);
      }
      add_standstills(block);
    }
    add_grid(block);
    add_drive(block);
    gnss_rows_before_ += gnss_last - gnss_first;
  }

  // The forward reading over the drive, on hills with the altitude's grade taken out of a copy of
  // the block (as the preparation does).
  void add_drive(const PreparedBlock& block) {
    const Log& log = block.context;
    if (!log.imu || log.wheels.size() < 2) return;
    const double from = block.first ? log.wheels.t_s.front() : block.core_from_s;
    std::optional<Log> projected;
    const CalibrationOptions defaults;
    if (const auto profile = grade_from_gnss_altitude(log, nominal_, defaults.grade_window_m)) {
      projected = log;
      project_to_horizontal(*projected, *profile);
    }
    drive_->add(projected ? *projected : log, from, block.core_to_s, projected.has_value());
  }

  void add_repeats(const GnssStream& gnss, std::size_t first, std::size_t last) {
    for (std::size_t k = std::max<std::size_t>(first, 1); k < last; ++k) {
      if (gnss.x_m[k] == gnss.x_m[k - 1] && gnss.y_m[k] == gnss.y_m[k - 1]) {
        if (facts_.gnss_repeated++ == 0)
          facts_.gnss_first_repeated_row = gnss_rows_before_ + (k - first);
      }
    }
  }

  void add_gnss_gaps(const GnssStream& gnss, std::size_t first, std::size_t last) {
    std::vector<double> dt;
    for (std::size_t k = std::max<std::size_t>(first, 1); k < last; ++k)
      dt.push_back(gnss.t_s[k] - gnss.t_s[k - 1]);
    if (dt.empty()) return;
    const double longest = *std::max_element(dt.begin(), dt.end());
    const double typical = median(std::move(dt));
    if (longest > std::max(2.0, 10.0 * typical) &&
        (!facts_.gnss_gap || longest > facts_.gnss_gap->first))
      facts_.gnss_gap = {longest, typical};
  }

  void add_standstills(const PreparedBlock& block) {
    const Log& log = block.context;
    const double from = block.first ? log.wheels.t_s.front() : block.core_from_s;
    std::vector<Standstill> own;
    for (const Standstill& still : find_standstills(log, nominal_, {})) {
      const Standstill clipped{std::max(still.start_s, from),
                               std::min(still.end_s, block.core_to_s)};
      if (clipped.end_s > clipped.start_s) own.push_back(clipped);
    }
    if (own.empty()) return;
    facts_.standing = true;
    if (log.imu) {
      const auto add_window = [&](const std::vector<double>& values, WindowSum& total,
                                  const Standstill& still) {
        const WindowSum window = window_sum(log.imu->t_s, values, still.start_s, still.end_s);
        total.sum += window.sum;
        total.sum_squares += window.sum_squares;
        total.count += window.count;
      };
      for (const Standstill& still : own) {
        add_window(log.imu->wz_radps, facts_.gyro_standing, still);
        add_window(log.imu->ax_mps2, facts_.ax_standing, still);
      }
    }
    if (rate_sensor(log.wheels.unit_rear)) {
      const WheelRateBias bias = wheel_rate_bias(log.wheels, own);
      bias_sum_.rl_rev_per_s += bias.standing_s * bias.rl_rev_per_s;
      bias_sum_.rr_rev_per_s += bias.standing_s * bias.rr_rev_per_s;
      bias_standing_s_ += bias.standing_s;
    }
  }

  // The grid starts where wheels and GNSS both have begun; each block adds its own rows.
  void add_grid(const PreparedBlock& block) {
    const Log& log = block.context;
    if (log.wheels.size() < 2 || log.gnss.t_s.empty()) return;
    if (!grid_from_) grid_from_ = std::max(facts_.wheels.first_s, log.gnss.t_s.front());
    const auto row_at_or_after = [&](double t_s) -> std::size_t {
      const double position = std::ceil((t_s - *grid_from_) / step_s_ - 0.5);
      return position <= 0.0 ? 0 : static_cast<std::size_t>(position);
    };
    const std::size_t first = row_at_or_after(block.core_from_s);
    const std::size_t last =
        block.last ? std::numeric_limits<std::size_t>::max() : row_at_or_after(block.core_to_s);
    append_diagnosis_signals(log, *grid_from_, step_s_, std::max(first, signals_.size()), last,
                             signals_);
  }

  LogBlockSource& source_;
  DiagnosisSignals& signals_;
  double step_s_;
  DiagnosisFacts facts_;
  OdometryParams nominal_;
  std::optional<DriveForwardMeasure> drive_;
  std::size_t gnss_rows_before_{};
  std::optional<double> grid_from_;
  WheelRateBias bias_sum_;
  double bias_standing_s_{};
};

}  // namespace

DiagnosisFacts diagnosis_facts(LogBlockSource& source, DiagnosisSignals& signals, double step_s) {
  return FactGathering(source, signals, step_s).run();
}

}  // namespace odocal::detail
