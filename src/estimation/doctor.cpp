// The doctor's run: which checks follow from which, and the findings that a finding explains
// away (a Doppler speed in another unit, a mirrored track, wheels in a wrong unit).
#include "doctor.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace odocal::detail {

Doctor::Doctor(DiagnosisFacts facts, DiagnosisSignals signals)
    : facts_(std::move(facts)), signals_(std::move(signals)) {
  moving_.resize(signals_.size());
  turning_.resize(signals_.size());
  for (std::size_t k = 0; k < signals_.size(); ++k) {
    moving_[k] = signals_.gnss_speed_mps[k] > 3.0;
    const double gyro = signals_.gyro_radps.empty() ? 0.0 : signals_.gyro_radps[k];
    turning_[k] =
        moving_[k] && (std::abs(signals_.wheel_yaw_rate_radps[k]) > 0.05 || std::abs(gyro) > 0.05);
  }
}

Diagnosis Doctor::run() {
  out_.compared_s = seconds(signals_.size());
  const bool clocks_agree = check_spans();
  if (signals_.size() > 0 && clocks_agree) {
    const bool signs_ok = check_wheel_speeds();
    if (signs_ok) check_yaw_rates();
    check_clock_offsets();
    check_drive_force_clock();
    if (signs_ok) check_track_width();
    if (signs_ok) check_imu_axes();
    if (signs_ok) check_imu_place();
    if (signs_ok) check_heading_offset();
    // The wheels were compared with the Doppler speed where there is one: in another unit it
    // makes right wheels look wrong by its factor.
    if (check_doppler_unit()) {
      std::erase_if(out_.findings, [](const Finding& f) {
        return f.check.starts_with("vehicle.") ||
               (f.check.starts_with("wheels.") && f.check.ends_with("_unit"));
      });
    } else if (signs_ok) {
      check_gnss_place();
    }
    // A mirrored GNSS track (lat/lon swapped) also scales its distances by direction: the
    // wheel ratios then say nothing about units or circumferences.
    if (has("gnss.mirrored")) {
      std::erase_if(out_.findings, [](const Finding& f) {
        return f.check.starts_with("vehicle.") || f.check.ends_with("_unit");
      });
    }
    // The gyro is judged against the wheels' yaw rate: wheels in a wrong unit (which the GNSS
    // confirms) make a right gyro look wrong by the same factor.
    if (has("wheels.rl_unit") || has("wheels.rr_unit")) {
      std::erase_if(out_.findings, [](const Finding& f) { return f.check == "imu.yaw_unit"; });
    }
  }
  check_gnss_repeats();
  // Stale repeated positions lag the track and distort its speed: no clock offset and no
  // circumference can be read from it until they are gone.
  if (has("gnss.repeated")) {
    std::erase_if(out_.findings, [](const Finding& f) {
      return f.check == "time.gnss_offset" || f.check.starts_with("vehicle.");
    });
  }
  check_gaps();
  check_standstill_biases();
  check_altitude();
  return std::move(out_);
}

}  // namespace odocal::detail
