// The doctor's check of the streams' clock offsets: each stream's delay against the wheels.
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <string_view>
#include <vector>

#include "doctor.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/tyre_model.hpp"

namespace odocal::detail {

std::vector<double> Doctor::wheel_acceleration() const {
  const auto half = static_cast<std::size_t>(std::lround(0.5 / signals_.step_s));
  std::vector<double> acceleration(signals_.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = half; half > 0 && k + half < signals_.size(); ++k) {
    const auto speed = [&](std::size_t i) {
      return 0.5 * (signals_.speed_rl_mps[i] + signals_.speed_rr_mps[i]);
    };
    acceleration[k] =
        (speed(k + half) - speed(k - half)) / (2.0 * static_cast<double>(half) * signals_.step_s);
  }
  return acceleration;
}

std::vector<double> Doctor::wheel_course_rate() const {
  if (!facts_.vehicle.gnss_position_m) return signals_.wheel_yaw_rate_radps;
  const Eigen::Vector2d antenna = *facts_.vehicle.gnss_position_m;
  // The lead's rate between neighbouring rows, so that it is smoothed as the wheels' yaw rate
  // beside it (over their second): over the course rate's own 2 s it left a fifth of an antenna's
  // lag in (the urban drive's 0.6 s clock read 0.025 s late with the antenna 0.81 m behind).
  constexpr std::size_t half = 1;
  const auto lead = [&](std::size_t i) {
    const double speed = 0.5 * (signals_.speed_rl_mps[i] + signals_.speed_rr_mps[i]);
    const double turn = signals_.wheel_yaw_rate_radps[i];
    return std::atan2(turn * antenna.x(), speed - turn * antenna.y());
  };
  std::vector<double> rate(signals_.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = half; k + half < signals_.size(); ++k) {
    rate[k] =
        signals_.wheel_yaw_rate_radps[k] + angle_difference(lead(k + half), lead(k - half)) /
                                               (2.0 * static_cast<double>(half) * signals_.step_s);
  }
  return rate;
}

namespace {

constexpr double kMaxLagS = 5.0, kMinOffsetS = 0.15;
// The drive force against the accelerometer: a warning from kMinForceWarningS (clean simulated
// drives within 0.03 s once the IMU's own delay is added back), which the tyre model feels (the
// IMU 0.1 s late: 9.5 mm, below). Against the wheels alone blocking from kMinOffsetWithoutImuS,
// above a hard-driven wheel's slip lead.
constexpr double kMinForceWarningS = 0.06, kMinOffsetWithoutImuS = 0.3;

}  // namespace

void Doctor::check_clock_offsets() {
  // The IMU's clock where the yaw rates correlate at least kCleanPeak: blocking from kMinOffsetS,
  // a warning from kMinCleanOffsetS (five times the clean drives' largest lag; an IMU's own
  // filter delays it by a few hundredths).
  constexpr double kCleanPeak = 0.98, kMinCleanOffsetS = 0.05;
  std::vector<double> wheel_speed(signals_.size());
  for (std::size_t k = 0; k < signals_.size(); ++k)
    wheel_speed[k] =
        0.5 * (std::abs(signals_.speed_rl_mps[k]) + std::abs(signals_.speed_rr_mps[k]));
  // A stronger anti-correlation means the signals disagree in sign (swapped wheels, a negated
  // gyro): their best positive match is then a spurious lag, not a clock. A peak hardly above
  // the zero-lag correlation is the vehicle's own dynamics (the course trails the heading
  // through a turn by its side slip), not a clock.
  const auto shows_offset = [](const Lag& lag, double min_gain = 0.02) {
    return std::isfinite(lag.lag_s) && lag.peak >= 0.5 && lag.peak > -lag.trough &&
           std::abs(lag.lag_s) >= kMinOffsetS && lag.peak - lag.at_zero >= min_gain;
  };
  // A driven rear axle's wheels run ahead of the body by their drive slip, the more so the
  // softer the tyres: on tools/independent_drive.py's rear-driven car with a slip stiffness of 12
  // per unit load (a winter tyre's) the gyro and the accelerometer both trail the wheels by about
  // 0.2 s at no clock offset. A lag that size is said to be possibly that, and still blocks: a
  // real one puts the tyre model's circumferences 10-20 mm off (check_clock_offsets below).
  const bool rear_driven =
      facts_.vehicle.body_geometry().drivetrain.value_or(Drivetrain::kRear) != Drivetrain::kFront;
  const auto report = [&](const char* check, const char* stream, const Lag& lag,
                          FindingSeverity severity = FindingSeverity::kBlocking) {
    const bool imu = std::string_view(stream) == "IMU";
    const bool slip_sized = imu && rear_driven && std::abs(lag.lag_s) < kMinOffsetWithoutImuS;
    add(check, severity,
        fmt::format("the {} clock is offset from the wheels' by {:+.2f} s", stream, lag.lag_s),
        fmt::format("cross-correlation peaks at {:+.2f} s ({:.3f}; {:.3f} at zero lag)", lag.lag_s,
                    lag.peak, lag.at_zero),
        slip_sized ? "two loggers on different clocks, a latency not taken out, or (a lag this "
                     "small) the driven rear wheels running ahead of the body by their drive "
                     "slip on soft tyres, which --force calibrates through"
                   : "two loggers on different clocks, or a latency not taken out",
        fmt::format("time.offset_s: {:+.3f} for {} in the import map", -lag.lag_s, stream));
    out_.findings.back().estimate = lag.lag_s;
  };
  // The GNSS clock from two signals that must agree: the speeds alone would read drive slip
  // (wheels run ahead while accelerating) as a lag, the course rate alone is noisy.
  const Lag by_speed =
      cross_correlation_lag(wheel_speed, signals_.gnss_speed_mps, signals_.step_s, kMaxLagS);
  // The course only where the GNSS moves: read as 0 below 2 m/s, it held still through the start
  // of every turn from rest, and the urban drive's 0.6 s clocks read 0.11 s late on average
  // (0.04 s left out). Over the moving samples alone the correlations run higher and flatter,
  // and a clock gains about half as much over zero lag (0.3 s on the urban drive: 0.006-0.033
  // against 0.017-0.053), so the course's peak need gain only kCourseGain; the speeds' witness
  // below keeps the fast circuits' side slip out (Hockenheim, front-driven: +0.33 s by the
  // course, gaining 0.011, +0.03 s by the speeds with their slip taken out).
  constexpr double kCourseGain = 0.01;
  const Lag by_course = cross_correlation_lag(wheel_course_rate(), signals_.gnss_course_rate_radps,
                                              signals_.step_s, kMaxLagS);
  // The course also trails by an antenna's distance behind the axle over the speed (x / v), as a
  // clock would where the turns are all taken at one speed (unless vehicle.yaml states the
  // antenna, which wheel_course_rate turns as the antenna's course): an antenna 0.81 m behind
  // beside a 107 ms latency read +0.35 s on the urban drive. The speed is the same at any antenna;
  // with its drive slip taken out (the wheels' lead, their speed times the slip the acceleration
  // asks) it read that latency as 0.13 s with RTK fixes, and 0.02 s without one. So a clock the
  // course shows must show in the speed too.
  const std::vector<double> acceleration = wheel_acceleration();
  std::vector<double> slip_lead(acceleration.size());
  for (std::size_t k = 0; k < slip_lead.size(); ++k)
    slip_lead[k] = wheel_speed[k] * acceleration[k];
  const Lag by_slip_free_speed = partial_cross_correlation_lag(
      wheel_speed, signals_.gnss_speed_mps, slip_lead, signals_.step_s, kMaxLagS);
  const bool speed_disowns =
      std::isfinite(by_slip_free_speed.lag_s) &&
      !(std::copysign(1.0, by_course.lag_s) * by_slip_free_speed.lag_s >= kMinOffsetS);
  // Yaw rates carry a clock only where the car turns.
  const bool turns = count(turning_) >= 50;
  if (turns && std::isfinite(by_course.lag_s) && by_course.peak > 0.5) {
    if ((std::abs(by_course.lag_s - by_speed.lag_s) < 0.3 || !std::isfinite(by_speed.lag_s)) &&
        shows_offset(by_course, kCourseGain) && !speed_disowns)
      report("time.gnss_offset", "GNSS", by_course);
  } else if (std::abs(by_speed.lag_s) > 3 * kMinOffsetS && shows_offset(by_speed)) {
    report("time.gnss_offset", "GNSS", by_speed);
  }
  // A slow robot never passes the car-scale motion gate above; its gyro says when it turns.
  const std::size_t gyro_turning =
      static_cast<std::size_t>(std::count_if(signals_.gyro_radps.begin(), signals_.gyro_radps.end(),
                                             [](double w) { return std::abs(w) > 0.1; }));
  if ((turns || gyro_turning >= 100) && !signals_.gyro_radps.empty()) {
    // The IMU's clock from two signals that must agree, as the GNSS's: the yaw rates alone
    // read a rear-driven car's inner wheel, spinning out of every corner, as a lag (3 laps of
    // Hockenheim: +1.0 s, 0.85 against 0.82 at zero lag). Its forward acceleration against
    // the wheels' judges, where it varies enough to say anything.
    const Lag by_yaw = cross_correlation_lag(signals_.wheel_yaw_rate_radps, signals_.gyro_radps,
                                             signals_.step_s, kMaxLagS);
    const Lag by_acceleration =
        cross_correlation_lag(wheel_acceleration(), signals_.ax_mps2, signals_.step_s, kMaxLagS);
    // Where the two yaw rates match almost exactly at the peak, its lag is the clock's to a
    // hundredth of a second (the built-in scenarios' drives within 0.01 s, the Husky bag 0.000 s;
    // an IMU shifted by 0.2 s read as +0.19 s), however little it gains over zero lag (0.011
    // there: a smooth signal's correlation falls slowly). The tyre model takes each wheel
    // sample's force from the accelerometer at the wheels' time: an IMU 0.2 s late put a
    // rear-driven circuit's circumferences 21 mm off at a sigma of 5.7 mm, 0.1 s 9.5 mm at 4.7.
    const bool clean =
        std::isfinite(by_yaw.lag_s) && by_yaw.peak >= kCleanPeak && by_yaw.peak > -by_yaw.trough;
    const double offset_s = std::abs(by_yaw.lag_s);
    if (clean) imu_delay_s_ = by_yaw.lag_s;
    const bool yaw_shows = shows_offset(by_yaw) || (clean && offset_s >= kMinOffsetS);
    if (!(std::isfinite(by_acceleration.lag_s) && by_acceleration.peak > 0.5) ||
        std::abs(by_yaw.lag_s - by_acceleration.lag_s) < 0.3) {
      if (yaw_shows) {
        report("time.imu_offset", "IMU", by_yaw);
        imu_delay_s_ = by_yaw.lag_s;
      } else if (clean && offset_s >= kMinCleanOffsetS) {
        report("time.imu_offset", "IMU", by_yaw, FindingSeverity::kWarning);
      }
    } else if (yaw_shows || shows_offset(by_acceleration)) {
      // Disagreeing, neither is the clock's for sure: said, not blocked.
      add("time.imu_offset", FindingSeverity::kWarning,
          "the IMU clock cannot be checked against the wheels'",
          fmt::format("the yaw rates' cross-correlation peaks at {:+.2f} s ({:.2f}; {:.2f} at "
                      "zero lag), the forward accelerations' at {:+.2f} s ({:.2f}; {:.2f})",
                      by_yaw.lag_s, by_yaw.peak, by_yaw.at_zero, by_acceleration.lag_s,
                      by_acceleration.peak, by_acceleration.at_zero),
          "a driven wheel spinning out of the corners (its yaw rate trails them), or an IMU "
          "clock offset",
          "none for a car driven hard on a driven rear axle; otherwise time.offset_s for IMU "
          "in the import map");
    }
  }
}

void Doctor::check_drive_force_clock() {
  if (signals_.drive_force_mps2.empty()) return;
  // The force over the mass less the road's resistance is the body's acceleration at once: the
  // accelerometer's, whose own delay against the wheels (its filter's few hundredths, or the
  // offset found above) is added back. Without one, the wheels' acceleration, which leads the
  // force where a driven wheel slips hard: its slip follows the force, its speed the slip's rate
  // (Hockenheim's rear-driven circuit: +0.18 s on a clean log, the accelerometer's -0.01 s).
  const bool imu = !signals_.ax_mps2.empty();
  const Lag lag = cross_correlation_lag(imu ? signals_.ax_mps2 : wheel_acceleration(),
                                        signals_.drive_force_mps2, signals_.step_s, kMaxLagS);
  if (!(std::isfinite(lag.lag_s) && lag.peak >= 0.5 && lag.peak > -lag.trough)) return;
  const double offset_s = lag.lag_s + (imu ? imu_delay_s_ : 0.0);
  const double blocking_s = imu ? kMinOffsetS : kMinOffsetWithoutImuS;
  const double warning_s = imu ? kMinForceWarningS : blocking_s;
  if (std::abs(offset_s) < warning_s) return;
  add("time.drive_force_offset",
      std::abs(offset_s) >= blocking_s ? FindingSeverity::kBlocking : FindingSeverity::kWarning,
      fmt::format("wheels.csv's drive_force_n is offset from the wheels' clock by {:+.2f} s",
                  offset_s),
      fmt::format("its cross-correlation with the {} acceleration peaks at {:+.2f} s ({:.3f}; "
                  "{:.3f} at zero lag){}",
                  imu ? "accelerometer's forward" : "wheels'", lag.lag_s, lag.peak, lag.at_zero,
                  imu ? fmt::format(", the IMU {:+.2f} s from the wheels", imu_delay_s_)
                      : std::string(", without an IMU: a hard-driven wheel's slip leads by "
                                    "up to 0.2 s")),
      "the bus's signal logged on another clock, or its latency not taken out",
      fmt::format("time: {{offset_s: {:+.3f}}} in the import map's wheels.drive_force", -offset_s));
  out_.findings.back().estimate = offset_s;
}

}  // namespace odocal::detail
