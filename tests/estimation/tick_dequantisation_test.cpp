// Encoder quantisation in dead reckoning: two wheels rolling alike down a straight, their ticks
// cut at different phases, dead-reckon a heading of up to one tick's worth of track angle that
// never goes away; the counts' fitted line does not. Truth is exact: the drive is straight.

#include "odocal/estimation/tick_dequantisation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "odocal/estimation/batch_options.hpp"
#include "odocal/estimation/dead_reckoning.hpp"
#include "odocal/estimation/drift_validation.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/estimation/odometry_preintegration.hpp"

namespace odocal {
namespace {

constexpr double kTicksPerRev = 96.0;
constexpr double kRateHz = 50.0;
const OdometryParams kParams{1.96, 1.96, 1.6};
// The heading one tick of difference between the wheels turns: c / (n t).
const double kTickHeadingRad = kParams.circumference_rl_m / kTicksPerRev / kParams.track_width_m;

// Revolutions as floored counts of an encoder at `phase` (of a tick) when the wheel has turned
// `ticks`: the increments a tick logger gives.
struct Encoder {
  double phase{};
  double last{};
  double increment(double ticks) {
    const double count = std::floor(phase + ticks);
    const double revs = (count - last) / kTicksPerRev;
    last = count;
    return revs;
  }
};

// `speed(t)` m/s straight ahead, both wheels alike, encoders at the given phases.
template <class Speed>
WheelStream straight(double phase_rl, double phase_rr, double duration_s, Speed speed) {
  WheelStream w;
  Encoder rl{phase_rl, std::floor(phase_rl)}, rr{phase_rr, std::floor(phase_rr)};
  double ticks = 0.0;
  for (int k = 0; k <= static_cast<int>(duration_s * kRateHz); ++k) {
    const double t = k / kRateHz;
    if (k > 0)
      ticks += speed(t - 0.5 / kRateHz) / kRateHz / kParams.circumference_rl_m * kTicksPerRev;
    w.t_s.push_back(t);
    w.rev_rl.push_back(rl.increment(ticks));
    w.rev_rr.push_back(rr.increment(ticks));
  }
  return w;
}

// RMS heading over dead reckoning from sample `first` on (truth: zero).
double rms_heading_rad(const WheelStream& wheels, std::size_t first) {
  std::vector<Pose2> path(wheels.size() - first, Pose2::Zero());
  dead_reckon_into(wheels, first, kParams, path);
  double sum = 0.0;
  for (const Pose2& pose : path) sum += pose(2) * pose(2);
  return std::sqrt(sum / static_cast<double>(path.size()));
}

// 12.64 m/s: 12.38 ticks a sample, whose fraction (near the golden ratio's) sweeps a tick's
// phases evenly within the window. Where it is near a fraction of few digits (10.3 m/s: 10.09
// ticks a sample) the samples see few phases of the cut, and no average of them can see the rest
// (the sweep below).
const auto kSteady = [](double) { return 12.64; };

TEST(TickDequantisation, AStraightDeadReckonedFromMidDriveKeepsItsHeading) {
  for (const auto& [phase_rl, phase_rr] :
       {std::pair{0.05, 0.9}, std::pair{0.5, 0.1}, std::pair{0.3, 0.35}, std::pair{0.7, 0.2}}) {
    const WheelStream raw = straight(phase_rl, phase_rr, 60.0, kSteady);
    const WheelStream smoothed = dequantised_ticks(raw, kDefaultTickSmoothingS);
    for (const std::size_t first : {500u, 1234u}) {
      SCOPED_TRACE(testing::Message()
                   << "phases " << phase_rl << ", " << phase_rr << "; from " << first);
      EXPECT_LT(rms_heading_rad(smoothed, first), 0.05 * kTickHeadingRad);
      // The raw counts: the phase of the wheels' difference at the start of the dead reckoning
      // stays with it.
      if (std::abs(phase_rl - phase_rr) > 0.2) {
        EXPECT_GT(rms_heading_rad(raw, first), 0.2 * kTickHeadingRad);
      }
    }
  }
}

TEST(TickDequantisation, ALogStartingInMotionStartsOnTheFittedLine) {
  const WheelStream raw = straight(0.05, 0.9, 30.0, kSteady);
  EXPECT_GT(rms_heading_rad(raw, 0), 0.5 * kTickHeadingRad);  // one tick apart most of the time
  EXPECT_LT(rms_heading_rad(dequantised_ticks(raw, kDefaultTickSmoothingS), 0),
            0.2 * kTickHeadingRad);
}

// Every speed from 1 to 25 m/s, four pairs of phases: the resonances included, the smoothed
// counts' heading is a fraction of the raw counts', from mid-drive and from a rolling start.
TEST(TickDequantisation, EverySpeedGainsOnAverage) {
  double raw_mid = 0.0, smoothed_mid = 0.0, raw_start = 0.0, smoothed_start = 0.0;
  for (double speed = 1.0; speed <= 25.0; speed += 0.5) {
    for (const auto& [phase_rl, phase_rr] :
         {std::pair{0.05, 0.9}, std::pair{0.5, 0.1}, std::pair{0.3, 0.35}, std::pair{0.7, 0.2}}) {
      const WheelStream raw = straight(phase_rl, phase_rr, 12.0, [=](double) { return speed; });
      const WheelStream smoothed = dequantised_ticks(raw, kDefaultTickSmoothingS);
      raw_mid += rms_heading_rad(raw, 200);
      smoothed_mid += rms_heading_rad(smoothed, 200);
      raw_start += rms_heading_rad(raw, 0);
      smoothed_start += rms_heading_rad(smoothed, 0);
    }
  }
  EXPECT_LT(smoothed_mid, 0.25 * raw_mid);
  EXPECT_LT(smoothed_start, 0.5 * raw_start);
}

double total(const std::vector<double>& increments, std::size_t begin, std::size_t end) {
  double sum = 0.0;
  for (std::size_t k = begin; k < end; ++k) sum += increments[k];
  return sum;
}

// Standing, driving off, stopping, a gap, then the same again: at rest the count is what the
// encoder says, so every segment's total and every standstill stay exact, and the gap's sample
// keeps its zero.
TEST(TickDequantisation, CountsAtRestAndAtTheBreakStayAsCounted) {
  const auto stop_and_go = [](double t) {
    const double in_leg = std::fmod(t, 20.0);
    return in_leg < 3.0 || in_leg > 17.0 ? 0.0 : 8.0 * std::sin(M_PI * (in_leg - 3.0) / 14.0);
  };
  const WheelStream raw0 = straight(0.4, 0.8, 40.0, stop_and_go);
  WheelStream raw = raw0;
  const std::size_t gap = 1000;  // t = 20 s: standing
  raw.chain_break.assign(raw.size(), 0);
  raw.chain_break[gap] = 1;
  raw.rev_rl[gap] = raw.rev_rr[gap] = 0.0;
  const WheelStream smoothed = dequantised_ticks(raw, kDefaultTickSmoothingS);
  EXPECT_EQ(smoothed.rev_rl[gap], 0.0);
  for (const auto& [begin, end] : {std::pair<std::size_t, std::size_t>{1, gap},
                                   std::pair<std::size_t, std::size_t>{gap + 1, raw.size()}}) {
    EXPECT_NEAR(total(smoothed.rev_rl, begin, end), total(raw.rev_rl, begin, end), 1e-9);
    EXPECT_NEAR(total(smoothed.rev_rr, begin, end), total(raw.rev_rr, begin, end), 1e-9);
  }
  // Deep in a standstill (t = 21 s): nothing moves.
  EXPECT_EQ(smoothed.rev_rl[1050], 0.0);
  // While moving, the smoothed increments follow the motion and not the cut: within a tenth of
  // a tick of it wherever the speed changes slowly.
  double worst = 0.0;
  for (std::size_t k = 300; k < 700; ++k) {
    const double t = raw.t_s[k] - 0.5 / kRateHz;
    const double true_revs = stop_and_go(t) / kRateHz / kParams.circumference_rl_m;
    worst = std::max(worst, std::abs(smoothed.rev_rl[k] - true_revs) * kTicksPerRev);
  }
  EXPECT_LT(worst, 0.1);
}

// A stream that no preparation marked: its gap of 2 s (the counts of the gap in the sample after
// it) is no part of either side's average, and stays as counted.
TEST(TickDequantisation, AnUnmarkedGapIsNotAveragedOver) {
  const WheelStream whole = straight(0.05, 0.9, 20.0, kSteady);
  WheelStream gapped;
  for (std::size_t k = 0; k < whole.size(); ++k) {
    if (k > 500 && k < 600) continue;  // samples lost; sample 600 counts all of it
    gapped.t_s.push_back(whole.t_s[k]);
    gapped.rev_rl.push_back(k == 600 ? total(whole.rev_rl, 501, 601) : whole.rev_rl[k]);
    gapped.rev_rr.push_back(k == 600 ? total(whole.rev_rr, 501, 601) : whole.rev_rr[k]);
  }
  const WheelStream smoothed = dequantised_ticks(gapped, kDefaultTickSmoothingS);
  const std::size_t gap = 501;  // the sample after the gap, in the gapped stream
  EXPECT_EQ(smoothed.rev_rl[gap], gapped.rev_rl[gap]);
  EXPECT_EQ(smoothed.rev_rr[gap], gapped.rev_rr[gap]);
  EXPECT_NEAR(total(smoothed.rev_rl, 1, gap), total(gapped.rev_rl, 1, gap), 1.0 / kTicksPerRev);
  // Either side is smoothed as a stream of its own: the heading from mid-drive stays put.
  EXPECT_LT(rms_heading_rad(smoothed, gap + 100), 0.05 * kTickHeadingRad);
}

TEST(TickDequantisation, WheelAnglesAndAZeroWindowPassUnchanged) {
  WheelStream raw = straight(0.05, 0.9, 10.0, kSteady);
  EXPECT_EQ(dequantised_ticks(raw, 0.0).rev_rl, raw.rev_rl);
  raw.unit_rear = WheelUnit::kRadians;
  EXPECT_EQ(dequantised_ticks(raw, kDefaultTickSmoothingS).rev_rl, raw.rev_rl);
}

// The batch's preparation (heading_dequantised_ticks): only the wheels' difference is smoothed.
// A slalom at 12.64 m/s, yaw rate 0.3 rad/s swinging over 6 s, both encoders cut at their own
// phases; truth is the same drive's uncut increments.
struct Slalom {
  WheelStream cut, exact;
};

Slalom slalom(double phase_rl, double phase_rr, double duration_s) {
  Slalom s;
  Encoder rl{phase_rl, std::floor(phase_rl)}, rr{phase_rr, std::floor(phase_rr)};
  double ticks_rl = 0.0, ticks_rr = 0.0;
  const double half_track = 0.5 * kParams.track_width_m;
  for (int k = 0; k <= static_cast<int>(duration_s * kRateHz); ++k) {
    const double t = k / kRateHz;
    double step_rl = 0.0, step_rr = 0.0;
    if (k > 0) {
      const double yaw_rate = 0.3 * std::sin(2.0 * M_PI * (t - 0.5 / kRateHz) / 6.0);
      const double to_ticks = kTicksPerRev / kRateHz / kParams.circumference_rl_m;
      step_rl = (12.64 - half_track * yaw_rate) * to_ticks;
      step_rr = (12.64 + half_track * yaw_rate) * to_ticks;
    }
    ticks_rl += step_rl;
    ticks_rr += step_rr;
    for (WheelStream* w : {&s.cut, &s.exact}) w->t_s.push_back(t);
    s.cut.rev_rl.push_back(rl.increment(ticks_rl));
    s.cut.rev_rr.push_back(rr.increment(ticks_rr));
    s.exact.rev_rl.push_back(step_rl / kTicksPerRev);
    s.exact.rev_rr.push_back(step_rr / kTicksPerRev);
  }
  return s;
}

// RMS of the heading dead-reckoned from sample `first` against the exact increments'.
double rms_heading_error_rad(const WheelStream& wheels, const WheelStream& exact,
                             std::size_t first) {
  std::vector<Pose2> path(wheels.size() - first, Pose2::Zero());
  std::vector<Pose2> truth(wheels.size() - first, Pose2::Zero());
  dead_reckon_into(wheels, first, kParams, path);
  dead_reckon_into(exact, first, kParams, truth);
  double sum = 0.0;
  for (std::size_t k = 0; k < path.size(); ++k) {
    const double error = path[k](2) - truth[k](2);
    sum += error * error;
  }
  return std::sqrt(sum / static_cast<double>(path.size()));
}

const double kBatchHeadingSmoothingS = BatchOptions{}.heading_tick_smoothing_s;

TEST(HeadingDequantisation, TheDistanceStaysAsCountedSampleBySample) {
  const WheelStream raw = slalom(0.05, 0.9, 30.0).cut;
  const WheelStream smoothed = heading_dequantised_ticks(raw, kBatchHeadingSmoothingS);
  ASSERT_EQ(smoothed.size(), raw.size());
  for (std::size_t k = 0; k < raw.size(); ++k)
    ASSERT_NEAR(smoothed.rev_rl[k] + smoothed.rev_rr[k], raw.rev_rl[k] + raw.rev_rr[k], 1e-12)
        << "sample " << k;
}

TEST(HeadingDequantisation, ASlalomsHeadingFollowsTheTurnsNotTheCut) {
  for (const auto& [phase_rl, phase_rr] :
       {std::pair{0.05, 0.9}, std::pair{0.5, 0.1}, std::pair{0.3, 0.35}, std::pair{0.7, 0.2}}) {
    const Slalom drive = slalom(phase_rl, phase_rr, 30.0);
    const WheelStream smoothed = heading_dequantised_ticks(drive.cut, kBatchHeadingSmoothingS);
    for (const std::size_t first : {0u, 377u, 1000u}) {
      SCOPED_TRACE(testing::Message()
                   << "phases " << phase_rl << ", " << phase_rr << "; from " << first);
      const double raw = rms_heading_error_rad(drive.cut, drive.exact, first);
      const double dequantised = rms_heading_error_rad(smoothed, drive.exact, first);
      // Mid-drive (measured 0.07-0.12 of a tick's heading against 0.4-1.0 raw); from the first
      // sample, whose window is cut short and carries the quadratic out to it, 0.07-0.35.
      if (first > 0) {
        EXPECT_LT(dequantised, 0.5 * raw);
        EXPECT_GT(raw, 0.3 * kTickHeadingRad);
        EXPECT_LT(dequantised, 0.15 * kTickHeadingRad);
      } else {
        EXPECT_LT(dequantised, 0.4 * kTickHeadingRad);
      }
    }
  }
}

// Uncut counts of a slalom: nothing to take out, and the fit must not bend the turns. A line
// through +-h would leave h^2/6 times the difference's second derivative in the heading, the
// yaw rate's change (0.31 rad/s^2 at most here): 0.0033 rad at +-0.25 s, a quarter of a tick's
// heading, which shifted the ideal circuit's fitted scale.
TEST(HeadingDequantisation, ExactCountsKeepTheirTurnsCurvature) {
  const Slalom drive = slalom(0.05, 0.9, 30.0);
  const WheelStream smoothed = heading_dequantised_ticks(drive.exact, kBatchHeadingSmoothingS);
  for (const std::size_t first : {0u, 377u, 1000u}) {
    SCOPED_TRACE(testing::Message() << "from " << first);
    EXPECT_LT(rms_heading_error_rad(smoothed, drive.exact, first), 0.02 * kTickHeadingRad);
  }
}

// The errors' squared deviations from their mean, summed (a cut count's phase at the start is a
// constant).
double squared_deviations(const std::vector<double>& errors) {
  double mean = 0.0, square = 0.0;
  for (const double e : errors) mean += e / static_cast<double>(errors.size());
  for (const double e : errors) square += (e - mean) * (e - mean);
  return square;
}

// Why the batch keeps the inner samples' cut whole in its segments' covariance: the smoothing
// moves each count's error onto its neighbours without shrinking it, so the heading error summed
// over a keyframe interval (what walks the path sideways) is the cut's, where the error at one
// sample is a small share of it.
TEST(HeadingDequantisation, TheSmoothingSpreadsTheCutWithoutShrinkingItsSum) {
  const Slalom drive = slalom(0.05, 0.9, 30.0);
  const WheelStream smoothed = heading_dequantised_ticks(drive.cut, kBatchHeadingSmoothingS);
  std::vector<double> raw, left;
  double cut_difference = 0.0, smoothed_difference = 0.0, exact_difference = 0.0;
  for (std::size_t k = 1; k < smoothed.size(); ++k) {
    cut_difference += drive.cut.rev_rr[k] - drive.cut.rev_rl[k];
    smoothed_difference += smoothed.rev_rr[k] - smoothed.rev_rl[k];
    exact_difference += drive.exact.rev_rr[k] - drive.exact.rev_rl[k];
    raw.push_back(cut_difference - exact_difference);
    left.push_back(smoothed_difference - exact_difference);
  }
  const auto interval_sums = [](const std::vector<double>& errors) {
    const std::size_t interval = std::lround(kRateHz);  // the batch's 1 s keyframes
    std::vector<double> sums;
    for (std::size_t from = 100; from + interval + 100 <= errors.size(); from += interval) {
      sums.push_back(total(errors, from, from + interval));
    }
    return sums;
  };
  const double summed =
      std::sqrt(squared_deviations(interval_sums(left)) / squared_deviations(interval_sums(raw)));
  const double at_a_sample = std::sqrt(squared_deviations(left) / squared_deviations(raw));
  EXPECT_GT(summed, 0.7);
  EXPECT_LT(summed, 1.3);
  EXPECT_LT(at_a_sample, 0.5 * summed);
}

TEST(HeadingDequantisation, BreaksAnglesAndAZeroWindowAreKept) {
  WheelStream raw = slalom(0.4, 0.8, 20.0).cut;
  const std::size_t gap = 500;
  raw.chain_break.assign(raw.size(), 0);
  raw.chain_break[gap] = 1;
  raw.rev_rl[gap] = raw.rev_rr[gap] = 0.0;
  const WheelStream smoothed = heading_dequantised_ticks(raw, kBatchHeadingSmoothingS);
  EXPECT_EQ(smoothed.rev_rl[gap], 0.0);
  EXPECT_EQ(smoothed.rev_rr[gap], 0.0);
  // Each side of the break is smoothed on its own: in motion, its total moves by less than a tick.
  for (const auto& [begin, end] : {std::pair<std::size_t, std::size_t>{1, gap},
                                   std::pair<std::size_t, std::size_t>{gap + 1, raw.size()}}) {
    EXPECT_NEAR(total(smoothed.rev_rl, begin, end), total(raw.rev_rl, begin, end),
                1.0 / kTicksPerRev);
    EXPECT_NEAR(total(smoothed.rev_rr, begin, end), total(raw.rev_rr, begin, end),
                1.0 / kTicksPerRev);
  }
  // The sample after the break is not averaged with the one before: the right side's heading
  // from mid-drive is as good as a stream of its own.
  EXPECT_LT(rms_heading_error_rad(smoothed, slalom(0.4, 0.8, 20.0).exact, gap + 100),
            0.2 * kTickHeadingRad);
  EXPECT_EQ(heading_dequantised_ticks(raw, 0.0).rev_rl, raw.rev_rl);
  raw.unit_rear = WheelUnit::kRadians;
  EXPECT_EQ(heading_dequantised_ticks(raw, kBatchHeadingSmoothingS).rev_rr, raw.rev_rr);
}

// The batch fits the log's own stream with the change of each sample's difference beside it
// (CalibrationRun::batch_wheels): read through FittedWheels it is the smoothed copy, in the
// increments, the pre-integrated segments and the driving states, without copying the stream.
TEST(HeadingDequantisation, TheStreamWithItsChangeReadsAsTheSmoothedCopy) {
  const WheelStream raw = slalom(0.05, 0.9, 30.0).cut;
  const WheelStream copy = heading_dequantised_ticks(raw, kBatchHeadingSmoothingS);
  const std::vector<double> change = heading_tick_change(raw, kBatchHeadingSmoothingS);
  ASSERT_EQ(change.size(), raw.size());
  const FittedWheels fitted(raw, change);
  EXPECT_EQ(&fitted.t_s, &raw.t_s);
  double moved = 0.0;
  for (std::size_t k = 0; k < raw.size(); ++k) {
    ASSERT_EQ(fitted.increment(k).rev_rl, copy.rev_rl[k]) << "sample " << k;
    ASSERT_EQ(fitted.increment(k).rev_rr, copy.rev_rr[k]) << "sample " << k;
    moved = std::max(moved, std::abs(change[k]));
  }
  EXPECT_GT(moved, 0.1 / kTicksPerRev);  // it smooths something
  const PreintegratedSegment from_view = preintegrate(fitted, 100, 150, kParams, WheelNoise{});
  const PreintegratedSegment from_copy = preintegrate(copy, 100, 150, kParams, WheelNoise{});
  EXPECT_EQ(from_view.delta.back(), from_copy.delta.back());
  EXPECT_EQ(from_view.covariance, from_copy.covariance);
  const std::vector<DrivingState> states_view = driving_states(fitted, nullptr, kParams);
  const std::vector<DrivingState> states_copy = driving_states(copy, nullptr, kParams);
  ASSERT_EQ(states_view.size(), states_copy.size());
  for (std::size_t k = 0; k < states_view.size(); ++k)
    ASSERT_EQ(states_view[k].yaw_rate_radps, states_copy[k].yaw_rate_radps) << "sample " << k;
  EXPECT_TRUE(heading_tick_change(raw, 0.0).empty());
}

// `validate` dead-reckons the smoothed counts unless told not to.
TEST(TickDequantisation, HeldOutWindowsDriftLessWithTheCountsSmoothed) {
  const WheelStream wheels = straight(0.05, 0.9, 185.0, kSteady);
  ReferenceTrajectory exact;
  for (const double t : wheels.t_s) exact.poses.emplace_back(12.64 * t, 0.0, 0.0);
  DriftValidationOptions options;
  options.step_s = 7.0;
  const double smoothed = validate_drift(wheels, exact, kParams, kParams, options)
                              .calibrated_statistics.median_end_error_m;
  options.tick_smoothing_s = 0.0;
  const double raw = validate_drift(wheels, exact, kParams, kParams, options)
                         .calibrated_statistics.median_end_error_m;
  EXPECT_LT(smoothed, 0.2 * raw);
  EXPECT_GT(raw, 0.5);  // a quarter of a tick's heading over 600 m
}

}  // namespace
}  // namespace odocal
