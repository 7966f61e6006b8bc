#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>
#include <optional>

#include "drive_force_check.hpp"
#include "odocal/io/stream_readers.hpp"
#include "table_checks.hpp"

namespace odocal {
namespace {

struct WheelColumn {
  std::string name;
  WheelUnit unit;
};

// The single column that gives wheel `prefix`, if any.
std::optional<WheelColumn> find_wheel_column(const CsvTable& table, std::string_view prefix) {
  std::optional<WheelColumn> found;
  for (const auto& [unit, unit_name] : EnumNames<WheelUnit>::kTable) {
    std::string name = fmt::format("{}_{}", prefix, unit_name);
    if (!table.has(name)) continue;
    if (found) {
      throw InputError({table.file, 1, name},
                       fmt::format("wheel '{}' is given twice ({} and {}); keep one column", prefix,
                                   found->name, name));
    }
    found = WheelColumn{std::move(name), unit};
  }
  return found;
}

class WheelConverter {
 public:
  WheelConverter(const CsvTable& table, const VehicleConfig& vehicle,
                 const WheelReadOptions& options)
      : table_(table), vehicle_(vehicle), options_(options), t_(table.column("t")) {}

  // Revolution increments of one wheel; index 0 is 0.
  std::vector<double> increments(const WheelColumn& column, double nominal_circumference_m) const {
    const std::vector<double>& values = table_.column(column.name);
    std::vector<double> revs(values.size(), 0.0);
    constexpr double kTwoPi = 2.0 * std::numbers::pi;
    switch (column.unit) {
      case WheelUnit::kTicks: {
        const double ticks_per_rev = require_ticks_per_rev(column.name);
        check_tick_values(column.name, values);
        for (std::size_t k = 1; k < values.size(); ++k) {
          revs[k] = unwrapped_tick_delta(values[k] - values[k - 1]) / ticks_per_rev;
        }
        break;
      }
      case WheelUnit::kRadians:
        for (std::size_t k = 1; k < values.size(); ++k) {
          revs[k] = (values[k] - values[k - 1]) / kTwoPi;
        }
        break;
      case WheelUnit::kRadiansPerSecond:
        check_speeds(column.name, values, nominal_circumference_m / kTwoPi);
        for (std::size_t k = 1; k < values.size(); ++k) {
          revs[k] = 0.5 * (values[k] + values[k - 1]) * (t_[k] - t_[k - 1]) / kTwoPi;
        }
        break;
      case WheelUnit::kMetresPerSecond:
        check_speeds(column.name, values, 1.0);
        for (std::size_t k = 1; k < values.size(); ++k) {
          revs[k] =
              0.5 * (values[k] + values[k - 1]) * (t_[k] - t_[k - 1]) / nominal_circumference_m;
        }
        break;
    }
    if (column.unit == WheelUnit::kTicks || column.unit == WheelUnit::kRadians) {
      check_jumps(column, revs, nominal_circumference_m);
    }
    return revs;
  }

 private:
  double require_ticks_per_rev(const std::string& column) const {
    if (!vehicle_.ticks_per_rev) {
      throw InputError(
          {options_.vehicle_file, 0, "ticks_per_rev"},
          fmt::format("required because {} gives column '{}' in ticks", table_.file, column));
    }
    return *vehicle_.ticks_per_rev;
  }

  void check_tick_values(const std::string& column, const std::vector<double>& values) const {
    for (std::size_t k = 0; k < values.size(); ++k) {
      if (values[k] != std::round(values[k])) {
        throw InputError(table_.at(k, column),
                         fmt::format("expected an integer tick count, got {}", values[k]));
      }
      if (vehicle_.counter_bits) {
        const double modulus = std::ldexp(1.0, *vehicle_.counter_bits);
        if (values[k] < -modulus / 2 || values[k] >= modulus) {
          throw InputError(table_.at(k, column),
                           fmt::format("{} does not fit a {}-bit counter (counter_bits in {})",
                                       values[k], *vehicle_.counter_bits, options_.vehicle_file));
        }
      }
    }
  }

  // Maps a raw counter difference into [-2^(bits-1), 2^(bits-1)) when the counter wraps.
  double unwrapped_tick_delta(double delta) const {
    if (!vehicle_.counter_bits) return delta;
    const double modulus = std::ldexp(1.0, *vehicle_.counter_bits);
    double wrapped = std::fmod(delta, modulus);
    if (wrapped >= modulus / 2) wrapped -= modulus;
    if (wrapped < -modulus / 2) wrapped += modulus;
    return wrapped;
  }

  void check_speeds(const std::string& column, const std::vector<double>& values,
                    double metres_per_unit) const {
    for (std::size_t k = 0; k < values.size(); ++k) {
      const double speed_mps = std::abs(values[k]) * metres_per_unit;
      if (speed_mps > options_.max_wheel_speed_mps) {
        throw InputError(table_.at(k, column),
                         fmt::format("implausible wheel speed {} ({:.1f} m/s; at most {} m/s "
                                     "expected)",
                                     values[k], speed_mps, options_.max_wheel_speed_mps));
      }
    }
  }

  void check_jumps(const WheelColumn& column, const std::vector<double>& revs,
                   double nominal_circumference_m) const {
    for (std::size_t k = 1; k < revs.size(); ++k) {
      const double dt_s = t_[k] - t_[k - 1];
      const double speed_mps = std::abs(revs[k]) * nominal_circumference_m / dt_s;
      if (speed_mps <= options_.max_wheel_speed_mps) continue;
      const std::string not_explained =
          column.unit != WheelUnit::kTicks ? fmt::format("is not plausible motion (at most {} m/s)",
                                                         options_.max_wheel_speed_mps)
          : vehicle_.counter_bits
              ? fmt::format(
                    "is neither plausible motion (at most {} m/s) nor a wrap of the "
                    "{}-bit counter",
                    options_.max_wheel_speed_mps, *vehicle_.counter_bits)
              : fmt::format(
                    "is neither plausible motion (at most {} m/s) nor a counter wrap (set "
                    "counter_bits in {} if the counter wraps)",
                    options_.max_wheel_speed_mps, options_.vehicle_file);
      throw InputError(table_.at(k, column.name),
                       fmt::format("jump of {:.4g} revolutions in {:.4g} s ({:.4g} m/s) {}",
                                   revs[k], dt_s, speed_mps, not_explained));
    }
  }

  const CsvTable& table_;
  const VehicleConfig& vehicle_;
  const WheelReadOptions& options_;
  const std::vector<double>& t_;
};

}  // namespace

WheelStream wheel_stream_from_table(const CsvTable& table, const VehicleConfig& vehicle,
                                    const WheelReadOptions& options) {
  detail::require_known_columns(
      table, {"t", "rl_ticks", "rl_rad", "rl_radps", "rl_mps", "rr_ticks", "rr_rad", "rr_radps",
              "rr_mps", "fl_ticks", "fl_rad", "fl_radps", "fl_mps", "fr_ticks", "fr_rad",
              "fr_radps", "fr_mps", "drive_force_n"});
  detail::require_increasing_time(table);
  detail::require_rows(table, 2, "need at least 2 samples to form a wheel increment");

  const auto rear_column = [&](std::string_view prefix) {
    auto column = find_wheel_column(table, prefix);
    if (!column) {
      throw InputError({table.file, 1, std::string(prefix) + "_*"},
                       fmt::format("required wheel column is missing (expected one of {0}_ticks, "
                                   "{0}_rad, {0}_radps, {0}_mps)",
                                   prefix));
    }
    return *column;
  };
  const WheelColumn rl = rear_column("rl");
  const WheelColumn rr = rear_column("rr");
  if (rl.unit != rr.unit) {
    throw InputError({table.file, 1, rr.name},
                     fmt::format("rear wheels use different units ({} and {})", rl.name, rr.name));
  }

  const WheelConverter converter(table, vehicle, options);
  WheelStream stream;
  stream.t_s = table.column("t");
  stream.unit_rear = rl.unit;
  stream.rev_rl = converter.increments(rl, vehicle.circumference_rl_m);
  stream.rev_rr = converter.increments(rr, vehicle.circumference_rr_m);

  const double rear_mean_m = 0.5 * (vehicle.circumference_rl_m + vehicle.circumference_rr_m);
  const auto fl = find_wheel_column(table, "fl");
  const auto fr = find_wheel_column(table, "fr");
  if (fl.has_value() != fr.has_value()) {
    throw InputError({table.file, 1, fl ? fl->name : fr->name},
                     "front wheels must be given as a pair (fl_* and fr_*)");
  }
  if (fl && fr) {
    stream.rev_fl = converter.increments(*fl, vehicle.circumference_fl_m.value_or(rear_mean_m));
    stream.rev_fr = converter.increments(*fr, vehicle.circumference_fr_m.value_or(rear_mean_m));
  }
  if (table.has("drive_force_n")) {
    detail::check_drive_force(table, stream, vehicle);
    stream.drive_force_n = table.column("drive_force_n");
  }
  return stream;
}

}  // namespace odocal
