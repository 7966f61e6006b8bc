#pragma once
// The log on one 10 Hz grid over the span wheels and GNSS share, as the doctor's checks compare
// them: each wheel's speed (nominal circumference), the yaw rate the wheels imply, the GNSS speed
// and course rate, the gyro rate, the lateral and forward accelerations, the heading stream's
// rate. A signal the log lacks is empty; a sample a signal cannot give (a standing GNSS has no
// course) is NaN.

#include <vector>

#include "odocal/data/log.hpp"

namespace odocal::detail {

struct DiagnosisSignals {
  double step_s{};
  std::vector<double> t_s;
  std::vector<double> speed_rl_mps, speed_rr_mps;  // signed, per wheel
  std::vector<double> wheel_yaw_rate_radps;
  std::vector<double> gnss_speed_mps;  // from positions (or the Doppler column)
  std::vector<double> gnss_course_rate_radps;
  // Over a 4 s baseline, for the wheel/GNSS distance ratio on straight driving: the speed of a
  // noisy track is biased high (|v + n| > |v|), by 3 % at parking speeds with 3 m of noise over
  // the 1 s baseline above, by a tenth of that over this one.
  std::vector<double> speed_long_rl_mps, speed_long_rr_mps;
  // The same baseline's speed from the GNSS positions alone, and the Doppler column at its centre
  // (empty without one): the Doppler speed's unit is judged against the positions.
  std::vector<double> position_speed_long_mps, doppler_speed_mps;
  // The GNSS speed the wheels are compared with over that baseline: Doppler where the log has it.
  const std::vector<double>& gnss_speed_long_mps() const {
    return doppler_speed_mps.empty() ? position_speed_long_mps : doppler_speed_mps;
  }
  std::vector<double> gyro_radps, ax_mps2, ay_mps2;  // empty without imu.csv
  std::vector<double> heading_rate_radps;            // empty without heading.csv
  // wheels.csv's drive_force_n over the body's mass, less the drag and rolling resistance at the
  // wheels' speed: the acceleration the force gives (empty without the column).
  std::vector<double> drive_force_mps2;
  // heading.csv less the course of the 4 s chord where it is straight (the wheels turn less than
  // kStraightChordRad over it) and forward at kCourseSpeedMps or more: a mount's yaw offset. NaN
  // elsewhere; empty without heading.csv. (Below 5 m/s too: the parking drive's straights, at
  // 2-4 m/s, find a 3 deg offset on 16 of 20 seeds, none from 5 m/s.)
  static constexpr double kStraightChordRad = 0.02;
  static constexpr double kCourseSpeedMps = 2.0;
  std::vector<double> heading_minus_course_rad;

  std::size_t size() const { return t_s.size(); }
};

// Empty (size 0) when wheels and GNSS share less than a few seconds.
DiagnosisSignals diagnosis_signals(const Log& log, double step_s = 0.1);

// Rows [first, last) of the grid t_i = from + (i + 1/2) step_s of a longer log, computed from
// this piece of it (which holds a few seconds either side of them), appended to `into`: a grid
// made a block at a time is the grid of the whole log. Rows beyond the piece's wheels or GNSS
// are left out.
void append_diagnosis_signals(const Log& log, double from, double step_s, std::size_t first,
                              std::size_t last, DiagnosisSignals& into);

// Least-squares slope of y on x through the origin, over samples where both are finite and
// `use` holds; NaN with fewer than `min_samples`.
double slope_through_origin(const std::vector<double>& x, const std::vector<double>& y,
                            const std::vector<bool>& use, std::size_t min_samples = 20);

// Pearson correlation over samples where both are finite and `use` holds; NaN when too few.
double correlation(const std::vector<double>& x, const std::vector<double>& y,
                   const std::vector<bool>& use, std::size_t min_samples = 20);

// The lag (s) by which `y` trails `x`, from the peak of their cross-correlation within
// +-max_lag_s (parabolic refinement), and the peak correlation; NaN when too few samples.
struct Lag {
  double lag_s{};
  double peak{};
  double at_zero{};
  double trough{};  // the most negative correlation in the window
};
Lag cross_correlation_lag(const std::vector<double>& x, const std::vector<double>& y, double step_s,
                          double max_lag_s);

// The same with `beside` (a signal at x's times) taken out of both: the peak of their partial
// correlation. For a lag that a third signal would otherwise lend its own delay to.
Lag partial_cross_correlation_lag(const std::vector<double>& x, const std::vector<double>& y,
                                  const std::vector<double>& beside, double step_s,
                                  double max_lag_s);

}  // namespace odocal::detail
