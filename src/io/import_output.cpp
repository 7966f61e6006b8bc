#include "odocal/io/import_output.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>

#include "odocal/error.hpp"
#include "odocal/estimation/calibration_options.hpp"
#include "odocal/estimation/motion_coverage.hpp"
#include "odocal/estimation/prepared_blocks.hpp"
#include "odocal/io/log_block_reader.hpp"

namespace odocal {
namespace {

namespace fs = std::filesystem;
constexpr std::size_t kFlushBytes = std::size_t{1} << 20;

// One stream's rows, rate and gaps, from its samples as they come. Stream files carry their
// times to the microsecond, so the median interval comes from a count per microsecond value.
class StreamTally {
 public:
  explicit StreamTally(std::string name) : name_(std::move(name)) {}
  void add(const std::vector<double>& t_s, std::size_t first, std::size_t last) {
    for (std::size_t k = first; k < last; ++k) {
      if (rows_ == 0) first_s_ = t_s[k];
      if (rows_ > 0) {
        const double dt = t_s[k] - last_s_;
        largest_gap_s_ = std::max(largest_gap_s_, dt);
        ++intervals_[std::llround(dt * 1e6)];
      }
      last_s_ = t_s[k];
      ++rows_;
    }
  }
  ImportedStreamSummary summary() const {
    ImportedStreamSummary out{name_, rows_, rows_ > 0 ? first_s_ : 0.0, 0.0, 0.0, 0.0};
    if (rows_ < 2) return out;
    out.duration_s = last_s_ - first_s_;
    out.largest_gap_s = largest_gap_s_;
    // The median interval (the upper one of an even count, as nth_element at n/2 picks it).
    const std::size_t wanted = (rows_ - 1) / 2;
    std::size_t seen = 0;
    for (const auto& [microseconds, count] : intervals_) {
      seen += count;
      if (seen > wanted) {
        out.median_rate_hz = 1e6 / static_cast<double>(microseconds);
        break;
      }
    }
    return out;
  }

 private:
  std::string name_;
  std::size_t rows_{};
  double first_s_{}, last_s_{}, largest_gap_s_{};
  std::map<long long, std::size_t> intervals_;
};

}  // namespace

StreamCsvWriter::StreamCsvWriter(const fs::path& path, const std::string& header,
                                 std::vector<int> decimals)
    : out_(path), decimals_(std::move(decimals)) {
  fmt::format_to(std::back_inserter(buffer_), "{}\n", header);
}

void StreamCsvWriter::add(double t_s, const double* values) {
  fmt::format_to(std::back_inserter(buffer_), "{:.6f}", t_s);
  for (std::size_t c = 0; c < decimals_.size(); ++c)
    fmt::format_to(std::back_inserter(buffer_), ",{:.{}f}", values[c], decimals_[c]);
  buffer_.push_back('\n');
  ++rows_;
  if (buffer_.size() >= kFlushBytes) flush();
}

void StreamCsvWriter::flush() {
  out_.write({buffer_.data(), buffer_.size()});
  buffer_.clear();
}

void StreamCsvWriter::commit() {
  flush();
  out_.commit();
}

void write_stream_csv(const fs::path& path, const std::string& header,
                      const std::vector<double>& t_s,
                      const std::vector<const std::vector<double>*>& columns,
                      const std::vector<std::size_t>& rows, const std::vector<int>& decimals) {
  StreamCsvWriter out(path, header, decimals);
  std::vector<double> values(columns.size());
  for (std::size_t k : rows) {
    for (std::size_t c = 0; c < columns.size(); ++c) values[c] = (*columns[c])[k];
    out.add(t_s[k], values.data());
  }
  out.commit();
}

ImportSummary check_staged_import(const fs::path& staged, const fs::path& target) {
  StreamTally wheels("wheels"), gnss("gnss"), imu("imu"), heading("heading"), truth("truth");
  bool has_imu = false, has_heading = false, has_truth = false;
  ImportSummary summary;
  try {
    LogBlockReader reader(staged);
    has_imu = fs::exists(staged / "imu.csv");
    has_heading = reader.has_heading();
    has_truth = reader.has_truth();
    const double start_s = reader.first_wheel_time_s();
    const OdometryParams nominal = reader.vehicle().nominal_params();
    LogBlocks blocks(reader, start_s, CalibrationOptions{}.prepare_block_s, start_s);
    std::optional<double> before_s;  // the last wheel sample of the block before
    while (const std::optional<PreparedBlock> block = blocks.next()) {
      const Log& log = block->context;
      const auto tally = [&](StreamTally& into, const std::vector<double>& t_s) {
        const auto [first, last] = core_rows(*block, t_s);
        into.add(t_s, first, last);
      };
      tally(wheels, log.wheels.t_s);
      tally(gnss, log.gnss.t_s);
      if (log.imu) tally(imu, log.imu->t_s);
      if (log.heading) tally(heading, log.heading->t_s);
      if (log.truth) tally(truth, log.truth->t_s);
      const auto [first, last] = core_rows(*block, log.wheels.t_s);
      if (first >= last) continue;
      summary.wheel_distance_m +=
          motion_coverage(log, nominal, before_s.value_or(log.wheels.t_s[first]),
                          log.wheels.t_s[last - 1])
              .distance_m;
      before_s = log.wheels.t_s[last - 1];
    }
    reader.finish();
  } catch (const InputError& e) {
    InputLocation location = e.location();
    if (location.file.starts_with(staged.string()))
      location.file = (target / fs::path(location.file).filename()).string();
    throw InputError(location, e.problem() + " (after conversion; nothing was written)");
  }
  summary.streams.push_back(wheels.summary());
  summary.streams.push_back(gnss.summary());
  if (has_imu) summary.streams.push_back(imu.summary());
  if (has_heading) summary.streams.push_back(heading.summary());
  if (has_truth) summary.streams.push_back(truth.summary());
  return summary;
}

}  // namespace odocal
