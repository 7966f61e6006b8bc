#pragma once
// The doctor (docs/doctor.md): every check of a log's facts and signals, each adding findings
// with their evidence, cause and fix. Its checks live by stream: doctor_streams.cpp (spans, gaps,
// repeats, altitude), doctor_wheels.cpp (units, signs, yaw rates, track width), doctor_clocks.cpp
// (clock offsets), doctor_sensors.cpp (IMU axes, Doppler unit, standstill biases),
// doctor_antenna.cpp (the GNSS antenna's place).

#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "diagnosis_facts.hpp"
#include "diagnosis_signals.hpp"
#include "odocal/estimation/log_diagnosis.hpp"

namespace odocal::detail {

// Runs once: run() hands its findings over.
class Doctor {
 public:
  Doctor(DiagnosisFacts facts, DiagnosisSignals signals);

  Diagnosis run();

 private:
  void add(std::string check, FindingSeverity severity, std::string what, std::string evidence,
           std::string cause, std::string fix) {
    out_.findings.push_back({std::move(check), severity, std::move(what), std::move(evidence),
                             std::move(cause), std::move(fix)});
  }

  bool has(std::string_view check) const {
    return std::any_of(out_.findings.begin(), out_.findings.end(),
                       [&](const Finding& f) { return f.check == check; });
  }

  std::size_t count(const std::vector<bool>& use) const {
    return static_cast<std::size_t>(std::count(use.begin(), use.end(), true));
  }

  double seconds(std::size_t samples) const {
    return static_cast<double>(samples) * signals_.step_s;
  }

  // Time scale and span: the wheels' and GNSS's clocks must cover the same drive.
  bool check_spans();

  // An IMU or heading stream that covers much less of the wheels' span than the wheels do: the
  // reference has no gyro or heading for the rest.
  void check_optional_span(const char* file, const StreamSpan& span);

  // Each wheel's speed against the GNSS speed: sign, unit and circumference.
  bool check_wheel_speeds();

  // How many times faster `other` turns than the wheels, over clear turns of the wheels (a slope
  // would be diluted by the wheels' noise): the mean of other x sign(wheels) over the mean
  // |wheels|.
  double turn_scale(const std::vector<double>& wheels, const std::vector<double>& other) const;

  // Wheels, gyro and GNSS course must turn the same way at the same rate.
  void check_yaw_rates();

  // The wheels' forward acceleration over the second around each row: the difference of their
  // one-second mean speeds half a second either side, centred as the accelerometer's mean is.
  std::vector<double> wheel_acceleration() const;

  // The GNSS course rate as the wheels would turn it: their yaw rate, and where vehicle.yaml
  // states the antenna, the rate of its course's lead on the axle's, atan2(w x, v - w y).
  std::vector<double> wheel_course_rate() const;

  // Clock offsets between streams, from the cross-correlation of what both measure.
  void check_clock_offsets();
  // wheels.csv's drive_force_n against the body's acceleration (after check_clock_offsets, which
  // measures the IMU's delay).
  void check_drive_force_clock();

  // The lateral acceleration in a turn is speed x yaw rate, to the left.
  void check_imu_axes();

  // Where the accelerometer sits: one x ahead of the rear axle reads x dw/dt to the left beyond
  // the axle's v w, which vehicle.yaml's imu_x_m must state for layer 1 to take it out.
  void check_imu_place();

  // heading.csv against the GNSS course, driving straight: a mount's yaw offset.
  void check_heading_offset();

  // The Doppler column against the positions' own speed over the 4 s baseline, driving straight
  // (a chord cuts a turn short) above 5 m/s (the positions' noise then biases their speed by well
  // under a per cent). Returns whether it found the column in another unit.
  bool check_doppler_unit();

  // Where the GNSS antenna sits across the car: one y left of the rear axle's centre runs y w
  // slower in a left turn, which its Doppler speed shows (doctor_antenna.cpp).
  void check_gnss_place();

  void check_gnss_repeats();

  void check_gaps();

  void check_standstill_biases();
  void check_driving_forward_offset();

  void check_altitude();

  // The track the wheels roll on, from their yaw rate against the gyro's at rest speed, the
  // circumferences' scale (wheel against GNSS distance) taken out. Only where nothing else
  // scales the wheels' or the gyro's turn (a unit, a sign, a circumference far off).
  void check_track_width();

  DiagnosisFacts facts_;
  DiagnosisSignals signals_;
  std::vector<bool> moving_, turning_;
  double imu_delay_s_ = 0.0;  // the IMU's clock against the wheels', where the yaw rates tell it
  double distance_ratio_ = std::numeric_limits<double>::quiet_NaN();  // wheels / GNSS, straight
  Diagnosis out_;
};

}  // namespace odocal::detail
