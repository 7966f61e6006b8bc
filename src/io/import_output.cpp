#include "odocal/io/import_output.hpp"

#include <algorithm>

#include "odocal/error.hpp"
#include "odocal/estimation/motion_coverage.hpp"
#include "odocal/io/log_reader.hpp"
#include "odocal/io/text_output.hpp"

namespace odocal {
namespace {

namespace fs = std::filesystem;

ImportedStreamSummary summarise(const std::string& name, const std::vector<double>& t_s) {
  ImportedStreamSummary summary{name, t_s.size(), t_s.empty() ? 0.0 : t_s.front(), 0.0, 0.0, 0.0};
  if (t_s.size() < 2) return summary;
  summary.duration_s = t_s.back() - t_s.front();
  std::vector<double> dt(t_s.size() - 1);
  for (std::size_t k = 1; k < t_s.size(); ++k) dt[k - 1] = t_s[k] - t_s[k - 1];
  summary.largest_gap_s = *std::max_element(dt.begin(), dt.end());
  std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
  summary.median_rate_hz = 1.0 / dt[dt.size() / 2];
  return summary;
}

}  // namespace

void write_stream_csv(const fs::path& path, const std::string& header,
                      const std::vector<double>& t_s,
                      const std::vector<const std::vector<double>*>& columns,
                      const std::vector<std::size_t>& rows, const std::vector<int>& decimals) {
  write_text_file(path, [&](TextBuffer& out) {
    out.print("{}\n", header);
    for (std::size_t k : rows) {
      out.print("{:.6f}", t_s[k]);
      for (std::size_t c = 0; c < columns.size(); ++c)
        out.print(",{:.{}f}", (*columns[c])[k], decimals[c]);
      out.print("\n");
    }
  });
}

ImportSummary check_staged_import(const fs::path& staged, const fs::path& target) {
  Log log;
  try {
    log = read_log(staged);
  } catch (const InputError& e) {
    InputLocation location = e.location();
    if (location.file.starts_with(staged.string()))
      location.file = (target / fs::path(location.file).filename()).string();
    throw InputError(location, e.problem() + " (after conversion; nothing was written)");
  }
  ImportSummary summary;
  summary.streams.push_back(summarise("wheels", log.wheels.t_s));
  summary.streams.push_back(summarise("gnss", log.gnss.t_s));
  if (log.imu) summary.streams.push_back(summarise("imu", log.imu->t_s));
  if (log.heading) summary.streams.push_back(summarise("heading", log.heading->t_s));
  if (log.truth) summary.streams.push_back(summarise("truth", log.truth->t_s));
  summary.wheel_distance_m = motion_coverage(log, log.vehicle.nominal_params(),
                                             log.wheels.t_s.front(), log.wheels.t_s.back())
                                 .distance_m;
  return summary;
}

}  // namespace odocal
