#pragma once
// A plain fit whose bias comes from the turns: with the track width taken as exact it is off
// beyond 3 of its sigma; with the track's uncertainty (track_width_uncertainty, the default) its
// sigma covers the error. Unjudged, so that neither check leans on the tyre models. Returns the
// fit with the track taken as exact.

#include <gtest/gtest.h>

#include <cmath>

#include "odocal/data/log.hpp"
#include "odocal/estimation/batch_calibration.hpp"
#include "unjudged_options.hpp"

namespace odocal::testing {

inline BatchSummary plain_fit_with_the_track_exact(const Log& log, BatchOptions options) {
  options.tyre_model = TyreModelChoice::kNone;
  options.track_width_uncertainty = 0.0;
  return calibrate_batch(log, options, unjudged_options());
}

inline BatchSummary expect_the_track_held_covers_the_plain_bias(const Log& log,
                                                                BatchOptions options,
                                                                double truth_m) {
  const BatchSummary exact = plain_fit_with_the_track_exact(log, options);
  EXPECT_GT(std::abs(exact.estimate.circumference_rl_m - truth_m), 3.0 * exact.sigma_rl_m())
      << exact.full_report();
  options.tyre_model = TyreModelChoice::kNone;
  const BatchSummary held = calibrate_batch(log, options, unjudged_options());
  EXPECT_LT(std::abs(held.estimate.circumference_rl_m - truth_m), 3.0 * held.sigma_rl_m())
      << held.full_report();
  EXPECT_NE(held.full_report().find("from the track width held"), std::string::npos)
      << held.full_report();
  return exact;
}

}  // namespace odocal::testing
