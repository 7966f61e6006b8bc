#include "odocal/io/log_block_reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <optional>
#include <system_error>

#include "odocal/data/stream_columns.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/log_window.hpp"
#include "odocal/io/csv_table.hpp"
#include "odocal/io/input_file.hpp"
#include "odocal/io/stream_readers.hpp"
#include "odocal/io/vehicle_config_io.hpp"

namespace odocal {
namespace {

namespace fs = std::filesystem;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr std::size_t kChunkRows = std::size_t{1} << 16;

// The last row of a table, as a table of its own.
CsvTable last_row(const CsvTable& table) {
  CsvTable row;
  row.file = table.file;
  row.header = table.header;
  for (const std::vector<double>& column : table.columns) row.columns.push_back({column.back()});
  row.line_of_row = {table.line_of_row.back()};
  return row;
}

// `row` (the previous chunk's last) in front of `table`: the checks that compare a row with the
// one before (time increasing, wheel increments) see across the chunk boundary.
CsvTable with_row_before(const CsvTable& row, CsvTable table) {
  for (std::size_t c = 0; c < table.columns.size(); ++c)
    table.columns[c].insert(table.columns[c].begin(), row.columns[c].front());
  table.line_of_row.insert(table.line_of_row.begin(), row.line_of_row.front());
  return table;
}

void check_directory(const fs::path& directory) {
  std::error_code error;
  const auto status = fs::status(directory, error);
  if (error && error != std::errc::no_such_file_or_directory)
    throw InputError({directory.string(), 0, ""}, "cannot open: " + error.message());
  if (!fs::is_directory(status)) {
    throw InputError({directory.string(), 0, ""}, fs::exists(status)
                                                      ? "not a directory: a log is a directory"
                                                      : "log directory does not exist");
  }
}

// One stream's file, read forward in chunks: the samples inside the window that the blocks have
// not yet left behind, and what the whole file showed (for the checks that need all of it).
template <typename Stream>
class StreamFile {
 public:
  using Decode = std::function<Stream(const CsvTable&)>;
  StreamFile(const fs::path& path, Decode decode, double window_from_s, double window_to_s)
      : reader_(path), decode_(std::move(decode)), from_s_(window_from_s), to_s_(window_to_s) {}

  const std::string& file() const { return reader_.file(); }
  const Stream& buffer() const { return buffer_; }
  Stream& buffer() { return buffer_; }
  bool ended() const { return ended_; }
  // Over the whole file, before the window: its last time, and its first time at or after
  // `meet_s` (set before reading: the wheels' first time).
  std::optional<double> last_s() const { return last_s_; }
  std::optional<double> first_from_meet_s() const { return first_from_meet_s_; }
  void set_meet(double t_s) { meet_s_ = t_s; }
  std::size_t rows_in_window() const { return rows_in_window_; }

  // Reads until the buffer holds a sample at or after t_s, or the file ends.
  void fill_until(double t_s) {
    while (!ended_ && (buffer_.t_s.empty() || buffer_.t_s.back() < t_s)) read_chunk();
  }
  // Reads the rest of the file, checking every row, keeping none of it.
  void drain() {
    while (!ended_) {
      read_chunk();
      drop_rows_before(buffer_, buffer_.t_s.size());
    }
  }
  void forget_before(double t_s) {
    const auto first = std::lower_bound(buffer_.t_s.begin(), buffer_.t_s.end(), t_s);
    drop_rows_before(buffer_, static_cast<std::size_t>(first - buffer_.t_s.begin()));
  }
  Stream between(double from_s, double to_s) const {
    const auto [first, last] = rows_between(buffer_.t_s, from_s, to_s);
    return stream_rows(buffer_, first, last);
  }
  // Called with each part of the window as it is read (the wheels start their chain).
  std::function<void(Stream&)> on_window_part;

 private:
  void read_chunk() {
    std::optional<CsvTable> chunk = reader_.next(kChunkRows);
    if (!chunk) {
      if (!previous_) {  // a header and no rows: the decoder says what is missing
        CsvTable empty;
        empty.file = reader_.file();
        empty.header = reader_.header();
        empty.columns.resize(empty.header.size());
        decode_(empty);
      }
      ended_ = true;
      return;
    }
    CsvTable next_previous = last_row(*chunk);
    const std::size_t skip = previous_ ? 1 : 0;
    const Stream decoded =
        decode_(previous_ ? with_row_before(*previous_, std::move(*chunk)) : std::move(*chunk));
    previous_ = std::move(next_previous);
    last_s_ = decoded.t_s.back();
    if (!first_from_meet_s_) {
      const auto at = std::lower_bound(decoded.t_s.begin() + static_cast<std::ptrdiff_t>(skip),
                                       decoded.t_s.end(), meet_s_);
      if (at != decoded.t_s.end()) first_from_meet_s_ = *at;
    }
    auto [first, last] = rows_between(decoded.t_s, from_s_, to_s_);
    first = std::max(first, skip);
    if (first >= last) return;
    Stream part = stream_rows(decoded, first, last);
    rows_in_window_ += last - first;
    if (on_window_part) on_window_part(part);
    append_stream(buffer_, part);
  }

  CsvChunkReader reader_;
  Decode decode_;
  double from_s_, to_s_;
  std::optional<CsvTable> previous_;
  Stream buffer_{};
  bool ended_ = false;
  std::optional<double> last_s_, first_from_meet_s_;
  double meet_s_ = -kInfinity;
  std::size_t rows_in_window_ = 0;
};

}  // namespace

struct LogBlockReader::Streams {
  Streams(const fs::path& dir, const LogReadOptions& read_options, double from, double to)
      : directory(dir),
        source(dir.string()),
        vehicle(read_vehicle_config(dir / "vehicle.yaml")),
        options(read_options),
        window_from_s(from),
        window_to_s(to),
        wheels(dir / "wheels.csv", wheel_decoder(), from, to) {
    wheels.on_window_part = [this](WheelStream& part) {
      if (!chain_started) start_wheel_chain(part);
      chain_started = true;
    };
  }

  // The other streams, once the wheels' first chunk is read (they are checked against the
  // wheels' span). read_log reads the whole wheel file first, and so reports its errors first.
  void open_streams() {
    if (gnss) return;
    wheels.fill_until(-kInfinity);
    const double from = window_from_s, to = window_to_s;
    gnss.emplace(directory / "gnss.csv", gnss_decoder(), from, to);
    const auto optional_file = [&](const char* name) -> std::optional<fs::path> {
      const fs::path path = directory / name;
      if (input_exists(path)) return path;
      return std::nullopt;
    };
    if (const auto path = optional_file("imu.csv"))
      imu.emplace(
          *path, [](const CsvTable& t) { return imu_stream_from_table(t); }, from, to);
    if (const auto path = optional_file("heading.csv"))
      heading.emplace(
          *path, [](const CsvTable& t) { return heading_stream_from_table(t); }, from, to);
    if (options.read_truth) {
      if (const auto path = optional_file("truth.csv"))
        truth.emplace(
            *path, [](const CsvTable& t) { return pose_stream_from_table(t); }, from, to);
    }
    if (const std::optional<double> first = wheels_first_s()) {
      gnss->set_meet(*first);
      for_each_optional([&](auto& file) { file.set_meet(*first); });
    }
  }

  // A stream that has no sample inside the wheels' span is a clock mismatch, not data.
  void require_meeting(const auto& file) const {
    const auto first = wheels_first_s();
    const auto last = wheels.last_s();
    const auto inside = file.first_from_meet_s();
    if (first && last && inside && *inside <= *last) return;
    throw InputError({file.file(), 0, "t"},
                     fmt::format("no sample inside the wheel time span [{}, {}] s: streams must "
                                 "share one clock",
                                 first.value_or(0.0), last.value_or(0.0)));
  }

  typename StreamFile<WheelStream>::Decode wheel_decoder() {
    WheelReadOptions wheel_options = options.wheels;
    wheel_options.vehicle_file = (directory / "vehicle.yaml").string();
    return [this, wheel_options](const CsvTable& table) {
      return wheel_stream_from_table(table, vehicle, wheel_options);
    };
  }

  typename StreamFile<GnssStream>::Decode gnss_decoder() {
    return [this](const CsvTable& table) {
      GnssStream stream = gnss_stream_from_table(table, origin ? &*origin : nullptr);
      if (!origin) origin = stream.origin;
      return stream;
    };
  }

  // The wheels' first time over the whole file.
  std::optional<double> wheels_first_s() const { return wheels.first_from_meet_s(); }

  template <typename Visit>
  void for_each_optional(Visit&& visit) {
    if (imu) visit(*imu);
    if (heading) visit(*heading);
    if (truth) visit(*truth);
  }

  fs::path directory;
  std::string source;
  VehicleConfig vehicle;
  LogReadOptions options;
  double window_from_s, window_to_s;
  std::optional<GeodeticOrigin> origin;
  bool chain_started = false;
  StreamFile<WheelStream> wheels;
  std::optional<StreamFile<GnssStream>> gnss;
  std::optional<StreamFile<ImuStream>> imu;
  std::optional<StreamFile<HeadingStream>> heading;
  std::optional<StreamFile<PoseStream>> truth;
  double largest_from_s = -kInfinity;
  double keep_back_s = 0.0;
};

LogBlockReader::LogBlockReader(const fs::path& directory, const LogReadOptions& options,
                               double window_from_s, double window_to_s) {
  check_directory(directory);
  streams_ = std::make_unique<Streams>(directory, options, window_from_s, window_to_s);
}

LogBlockReader::~LogBlockReader() = default;

const std::string& LogBlockReader::source() const { return streams_->source; }
const VehicleConfig& LogBlockReader::vehicle() const { return streams_->vehicle; }

bool LogBlockReader::has_heading() {
  streams_->open_streams();
  return streams_->heading.has_value();
}

bool LogBlockReader::has_truth() {
  streams_->open_streams();
  return streams_->truth.has_value();
}

double LogBlockReader::first_wheel_time_s() {
  Streams& s = *streams_;
  s.wheels.fill_until(-kInfinity);
  if (s.wheels.buffer().t_s.empty()) finish();  // an empty window: finish says so
  return s.wheels.buffer().t_s.front();
}

bool LogBlockReader::wheels_reach(double t_s) {
  Streams& s = *streams_;
  s.wheels.fill_until(t_s);
  return !s.wheels.buffer().t_s.empty() && s.wheels.buffer().t_s.back() >= t_s;
}

void LogBlockReader::keep_back(double seconds) {
  streams_->keep_back_s = std::max(streams_->keep_back_s, seconds);
}

Log LogBlockReader::block(double from_s, double to_s) {
  Streams& s = *streams_;
  s.open_streams();
  Log log;
  log.source = s.source;
  log.vehicle = s.vehicle;
  s.wheels.fill_until(to_s);
  log.wheels = s.wheels.between(from_s, to_s);
  s.gnss->fill_until(to_s);
  log.gnss = s.gnss->between(from_s, to_s);
  const auto optional_block = [&](auto& file, auto& into) {
    if (!file) return;
    file->fill_until(to_s);
    auto part = file->between(from_s, to_s);
    if (!part.t_s.empty()) into = std::move(part);
  };
  optional_block(s.imu, log.imu);
  optional_block(s.heading, log.heading);
  optional_block(s.truth, log.truth);
  s.largest_from_s = std::max(s.largest_from_s, from_s);
  const double forget_s = s.largest_from_s - s.keep_back_s;
  s.wheels.forget_before(forget_s);
  s.gnss->forget_before(forget_s);
  s.for_each_optional([&](auto& file) { file.forget_before(forget_s); });
  return log;
}

void LogBlockReader::finish() {
  Streams& s = *streams_;
  s.wheels.drain();
  s.open_streams();
  s.gnss->drain();
  s.require_meeting(*s.gnss);
  s.for_each_optional([&](auto& file) {
    file.drain();
    s.require_meeting(file);
  });
  if (s.window_from_s > -kInfinity || s.window_to_s < kInfinity) {
    require_window_holds(s.wheels.rows_in_window(), s.gnss->rows_in_window(), s.window_from_s,
                         s.window_to_s, s.wheels_first_s().value_or(0.0),
                         s.wheels.last_s().value_or(0.0));
  }
}

Log LogBlockReader::read_whole() {
  Streams& s = *streams_;
  Log log;
  log.source = s.source;
  log.vehicle = s.vehicle;
  s.wheels.fill_until(kInfinity);
  log.wheels = std::move(s.wheels.buffer());
  s.open_streams();
  s.gnss->fill_until(kInfinity);
  s.require_meeting(*s.gnss);
  log.gnss = std::move(s.gnss->buffer());
  const auto whole = [&](auto& file, auto& into) {
    if (!file) return;
    file->fill_until(kInfinity);
    s.require_meeting(*file);
    into = std::move(file->buffer());
  };
  whole(s.imu, log.imu);
  whole(s.heading, log.heading);
  whole(s.truth, log.truth);
  if (s.window_from_s > -kInfinity || s.window_to_s < kInfinity) {
    require_window_holds(log.wheels.size(), log.gnss.size(), s.window_from_s, s.window_to_s,
                         s.wheels_first_s().value_or(0.0), s.wheels.last_s().value_or(0.0));
  }
  // Appended chunk by chunk, the columns hold spare capacity: give it back, a column at a time.
  const auto fit = [](auto& stream) {
    for_each_column([](auto& column) { column.shrink_to_fit(); }, stream);
  };
  fit(log.wheels);
  fit(log.gnss);
  if (log.imu) fit(*log.imu);
  if (log.heading) fit(*log.heading);
  if (log.truth) fit(*log.truth);
  return log;
}

}  // namespace odocal
