// The doctor's track check: the wheels' turn against the gyro's at rest speed, the load
// transfer's speed-squared share, a gyro bias and a left/right difference fitted beside it.

#include "estimation/diagnosis_track.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace odocal::detail {
namespace {

// Turns at 4-20 m/s (at `slowest` and 16 m/s faster); the wheels turn `scale` times the gyro's
// rate, plus `load` v^2 of it.
DiagnosisSignals turning_drive(double scale, double load, double gyro_bias, double asymmetry,
                               double slowest = 4.0) {
  DiagnosisSignals signals;
  signals.step_s = 0.1;
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.002);
  for (int k = 0; k < 6000; ++k) {
    const double t = 0.1 * k;
    const double v = slowest + 8.0 + 8.0 * std::sin(0.013 * t);
    const double yaw = 0.3 * std::sin(0.11 * t);
    signals.t_s.push_back(t);
    signals.gnss_speed_mps.push_back(v);
    signals.gyro_radps.push_back(yaw + gyro_bias + noise(random));
    signals.wheel_yaw_rate_radps.push_back(scale * yaw * (1.0 + load * v * v) + asymmetry * v +
                                           noise(random));
  }
  return signals;
}

TEST(DiagnosisTrack, FindsTheScaleAtRestBesideLoadBiasAndAsymmetry) {
  const DiagnosisSignals signals = turning_drive(1.1, 1e-3, 0.004, 2e-4);
  const WheelTurnScale turn = wheel_turn_scale(signals, std::vector<bool>(signals.size(), true));
  EXPECT_NEAR(turn.at_rest, 1.1, 3.0 * turn.sigma);
  EXPECT_LT(turn.sigma, 0.005);
  EXPECT_GT(turn.turning, 1000u);
}

TEST(DiagnosisTrack, SaysNothingWithoutTheGyroOrTurns) {
  DiagnosisSignals signals = turning_drive(1.0, 0.0, 0.0, 0.0);
  EXPECT_TRUE(
      std::isnan(wheel_turn_scale(signals, std::vector<bool>(signals.size(), false)).at_rest));
  signals.gyro_radps.clear();
  EXPECT_TRUE(
      std::isnan(wheel_turn_scale(signals, std::vector<bool>(signals.size(), true)).at_rest));
}

TEST(DiagnosisTrack, SaysNothingFromFastTurnsAlone) {
  // Above 10 m/s the scale at rest speed would be an extrapolation along v^2 only.
  const DiagnosisSignals fast = turning_drive(1.0, 1e-3, 0.0, 0.0, 10.5);
  const std::vector<bool> all(fast.size(), true);
  EXPECT_TRUE(std::isnan(wheel_turn_scale(fast, all).at_rest));
  EXPECT_FALSE(std::isnan(wheel_turn_scale(turning_drive(1.0, 1e-3, 0.0, 0.0, 8.0), all).at_rest));
}

}  // namespace
}  // namespace odocal::detail
