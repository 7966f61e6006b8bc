#pragma once
// Every per-sample column of a stream, so that cutting, appending and slicing a stream by time
// is written once for all of them. `visit` is called with the same column of each stream given
// (one stream, or several of the same type side by side). An optional column may be empty.

#include <algorithm>
#include <limits>
#include <type_traits>

#include "odocal/data/log.hpp"

namespace odocal {

template <typename Visit, typename... Streams>
void for_each_column(Visit&& visit, Streams&... s) {
  using Stream = std::remove_const_t<std::common_type_t<Streams...>>;
  if constexpr (std::is_same_v<Stream, WheelStream>) {
    visit(s.t_s...);
    visit(s.rev_rl...);
    visit(s.rev_rr...);
    visit(s.rev_fl...);
    visit(s.rev_fr...);
    visit(s.chain_break...);
    visit(s.side_slip_rad...);
    visit(s.grade...);
    visit(s.drive_force_n...);
  } else if constexpr (std::is_same_v<Stream, GnssStream>) {
    visit(s.t_s...);
    visit(s.x_m...);
    visit(s.y_m...);
    visit(s.altitude_m...);
    visit(s.sigma_m...);
    visit(s.speed_mps...);
  } else if constexpr (std::is_same_v<Stream, ImuStream>) {
    visit(s.t_s...);
    visit(s.ax_mps2...);
    visit(s.ay_mps2...);
    visit(s.wz_radps...);
  } else if constexpr (std::is_same_v<Stream, HeadingStream>) {
    visit(s.t_s...);
    visit(s.heading_rad...);
  } else {
    static_assert(std::is_same_v<Stream, PoseStream>);
    visit(s.t_s...);
    visit(s.pose...);
  }
}

// What a stream carries besides its columns.
template <typename Stream>
void copy_stream_attributes(Stream& to, const Stream& from) {
  if constexpr (std::is_same_v<Stream, WheelStream>) to.unit_rear = from.unit_rear;
  if constexpr (std::is_same_v<Stream, GnssStream>) to.origin = from.origin;
}

// Samples [first, last) of `stream` (indices), every column alike.
template <typename Stream>
Stream stream_rows(const Stream& stream, std::size_t first, std::size_t last) {
  Stream out{};
  copy_stream_attributes(out, stream);
  for_each_column(
      [&](auto& column, const auto& source) {
        if (source.empty()) return;
        column.assign(source.begin() + static_cast<std::ptrdiff_t>(first),
                      source.begin() + static_cast<std::ptrdiff_t>(last));
      },
      out, stream);
  return out;
}

// Samples with from_s <= t <= to_s, as indices [first, last).
inline std::pair<std::size_t, std::size_t> rows_between(const std::vector<double>& t_s,
                                                        double from_s, double to_s) {
  const auto first = std::lower_bound(t_s.begin(), t_s.end(), from_s);
  const auto last = std::upper_bound(first, t_s.end(), to_s);
  return {static_cast<std::size_t>(first - t_s.begin()),
          static_cast<std::size_t>(last - t_s.begin())};
}

// Removes the samples before index `first` (every column alike).
template <typename Stream>
void drop_rows_before(Stream& stream, std::size_t first) {
  for_each_column(
      [&](auto& column) {
        if (column.empty()) return;
        column.erase(column.begin(), column.begin() + static_cast<std::ptrdiff_t>(first));
      },
      stream);
}

// What a row of a column reads where the column was not known for it: NaN for a measured or
// derived quantity (a grade where a block had no altitude), zero for a flag (no chain break).
template <typename Column>
typename Column::value_type unknown_row() {
  using Value = typename Column::value_type;
  if constexpr (std::is_floating_point_v<Value>) return std::numeric_limits<Value>::quiet_NaN();
  return Value{};
}

// Appends every column of `tail` to `stream`. A column only one of them has gets the other's
// rows as unknown_row (a chain break found in the tail only, a block without altitude).
template <typename Stream>
void append_stream(Stream& stream, const Stream& tail) {
  if (stream.t_s.empty()) copy_stream_attributes(stream, tail);
  const std::size_t rows = stream.t_s.size(), more_rows = tail.t_s.size();
  for_each_column(
      [&](auto& column, const auto& more) {
        if (column.empty() && more.empty()) return;
        using Column = std::remove_reference_t<decltype(column)>;
        column.resize(rows, unknown_row<Column>());
        if (more.empty()) {
          column.resize(rows + more_rows, unknown_row<Column>());
        } else {
          column.insert(column.end(), more.begin(), more.end());
        }
      },
      stream, tail);
}

}  // namespace odocal
