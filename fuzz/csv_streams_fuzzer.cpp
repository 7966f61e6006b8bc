// Every CSV stream reader: the first byte picks the stream, the rest is the file. Whatever the
// bytes, a reader returns a stream with finite, strictly increasing time, or throws InputError.

#include <cmath>

#include "fuzz_support.hpp"
#include "odocal/io/csv_table.hpp"
#include "odocal/io/stream_readers.hpp"
#include "odocal/io/track_reader.hpp"

namespace {

using namespace odocal;

void require_increasing(const std::vector<double>& t_s) {
  for (std::size_t k = 0; k < t_s.size(); ++k) {
    fuzz::require(std::isfinite(t_s[k]));
    if (k > 0) fuzz::require(t_s[k] > t_s[k - 1]);
  }
}

void read(std::uint8_t stream, std::string_view text) {
  switch (stream % 6) {
    case 0: {
      VehicleConfig vehicle;
      vehicle.track_width_m = 1.6;
      vehicle.circumference_rl_m = vehicle.circumference_rr_m = 1.96;
      vehicle.ticks_per_rev = 96;
      vehicle.counter_bits = 16;
      const WheelStream wheels =
          wheel_stream_from_table(parse_csv_table(text, "wheels.csv"), vehicle, {});
      require_increasing(wheels.t_s);
      for (std::size_t k = 0; k < wheels.size(); ++k)
        fuzz::require(std::isfinite(wheels.rev_rl[k]) && std::isfinite(wheels.rev_rr[k]));
      break;
    }
    case 1: {
      const GnssStream gnss = gnss_stream_from_table(parse_csv_table(text, "gnss.csv"));
      require_increasing(gnss.t_s);
      for (std::size_t k = 0; k < gnss.size(); ++k)
        fuzz::require(std::isfinite(gnss.x_m[k]) && std::isfinite(gnss.y_m[k]));
      break;
    }
    case 2:
      require_increasing(imu_stream_from_table(parse_csv_table(text, "imu.csv")).t_s);
      break;
    case 3:
      require_increasing(heading_stream_from_table(parse_csv_table(text, "heading.csv")).t_s);
      break;
    case 4:
      require_increasing(pose_stream_from_table(parse_csv_table(text, "truth.csv")).t_s);
      break;
    default:
      for (const auto& point : track_centreline_from_table(
               parse_csv_table(text, "track.csv", {.header_may_be_comment = true})))
        fuzz::require(point.allFinite());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  fuzz::expect_only_odocal_errors([&] { read(data[0], fuzz::as_text(data + 1, size - 1)); });
  return 0;
}
