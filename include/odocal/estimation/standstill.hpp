#pragma once
// Where the vehicle stands still, decided by the wheels, the GNSS Doppler speed and the gyro
// together, and what standing still reveals: the zero-rate bias of angular-rate wheel sensors
// (a wheel-speed sensor that reads 1 deg/s at rest adds phantom distance and, left against right,
// phantom heading) and where the motion starts.

#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/options/option_fields.hpp"

namespace odocal {

struct StandstillOptions {
  double max_speed_mps = 0.05;         // wheel speed (nominal circumferences) below this...
  double min_duration_s = 1.0;         // ...for at least this long
  double max_gnss_speed_mps = 0.3;     // and the GNSS Doppler speed, where the log has it
  double max_turn_rate_radps = 0.035;  // and the gyro (2 deg/s: a bias passes, a turn does not)

  static OptionTable<StandstillOptions> fields();
  std::string validate() const;  // empty when valid
};

struct Standstill {
  double start_s{};
  double end_s{};
};

std::vector<Standstill> find_standstills(const Log& log, const OdometryParams& nominal,
                                         const StandstillOptions& options = {});

// The mean rate of each rear wheel while standing, in revolutions per second; only meaningful for
// angular-rate inputs (WheelUnit radps or mps: a counter or angle simply stops).
struct WheelRateBias {
  double rl_rev_per_s{};
  double rr_rev_per_s{};
  double standing_s{};  // over this much standing time
};

WheelRateBias wheel_rate_bias(const WheelStream& wheels, const std::vector<Standstill>& standing);

// Subtracts the bias from every increment.
void remove_wheel_rate_bias(WheelStream& wheels, const WheelRateBias& bias);

// Time of the first wheel sample moving faster than min_speed_mps; nullopt if it never does.
std::optional<double> first_motion_s(const WheelStream& wheels, const OdometryParams& nominal,
                                     double min_speed_mps);

}  // namespace odocal
