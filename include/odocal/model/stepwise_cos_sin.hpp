#pragma once
// cos and sin of a heading that moves in small steps along a trajectory. The calibration loop
// needs three per sample and iteration (EKF prediction, eq. 12's phi_k, whole-log dead
// reckoning), where a libm sincos is a large share of the work (docs/calibration.md, "Speed").
// Rotating the previous value by the small step takes a dozen multiplications and is exact to
// rounding (see below).

#include <cmath>

namespace odocal {

struct CosSin {
  double cos = 1.0;
  double sin = 0.0;
};

// Steps up to this size take the series below; larger ones call libm.
inline constexpr double kSmallAngleRad = 1.0 / 16.0;

// cos and sin of |angle_rad| <= kSmallAngleRad from their Taylor series through x^10 and x^9:
// the first omitted terms, x^12/12! and x^11/11!, are below 2e-21 there, thousands of times
// under half an ulp of the result. The polynomials in t = x^2 are evaluated by Estrin's scheme
// (pairs of terms in parallel), which is shorter than Horner's as a chain of dependent
// operations: the EKF waits on this value every step.
inline CosSin small_angle_cos_sin(double angle_rad) {
  const double t = angle_rad * angle_rad, t2 = t * t, t4 = t2 * t2;
  const double sin_series =
      (1.0 - t * (1.0 / 6.0)) + t2 * ((1.0 / 120.0) - t * (1.0 / 5040.0)) + t4 * (1.0 / 362880.0);
  const double cos_series = (1.0 - t * 0.5) + t2 * ((1.0 / 24.0) - t * (1.0 / 720.0)) +
                            t4 * ((1.0 / 40320.0) - t * (1.0 / 3628800.0));
  return {cos_series, angle_rad * sin_series};
}

// Remembers the last angle asked for; a nearby next one is reached by rotating by the
// difference. Each rotation adds a few ulp, so every kExactEvery-th value comes from libm and
// the error never exceeds ~1e-14.
class StepwiseCosSin {
 public:
  static constexpr int kExactEvery = 64;

  CosSin operator()(double angle_rad) {
    const double step_rad = angle_rad - angle_rad_;
    if (steps_since_exact_ < kExactEvery && std::abs(step_rad) <= kSmallAngleRad) {
      const CosSin step = small_angle_cos_sin(step_rad);
      value_ = {value_.cos * step.cos - value_.sin * step.sin,
                value_.sin * step.cos + value_.cos * step.sin};
      ++steps_since_exact_;
    } else {
      value_ = {std::cos(angle_rad), std::sin(angle_rad)};
      steps_since_exact_ = 0;
    }
    angle_rad_ = angle_rad;
    return value_;
  }

 private:
  double angle_rad_ = NAN;  // the first call always takes the exact branch
  CosSin value_;
  int steps_since_exact_ = kExactEvery;
};

}  // namespace odocal
