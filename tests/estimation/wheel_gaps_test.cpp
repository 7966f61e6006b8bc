// Gaps in the wheel stream break the odometry chain instead of being integrated: a 1.5 s gap in
// the middle of a turn moves the estimate by no more than the noise, whether the sample after
// the gap carries the counts of the whole gap (an encoder) or a held rate (a wheel-speed sensor).

#include "odocal/estimation/wheel_gaps.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "experiments/worn_circuit.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {

TEST(WheelGaps, FoundAboveFiveSamplePeriods) {
  WheelStream wheels;
  for (int k = 0; k < 100; ++k) wheels.t_s.push_back(0.02 * k + (k >= 50 ? 1.0 : 0.0));
  wheels.rev_rl.assign(100, 0.01);
  wheels.rev_rr.assign(100, 0.01);
  EXPECT_NEAR(default_max_wheel_gap_s(wheels), 0.1, 1e-12);
  const std::vector<WheelGap> gaps = find_wheel_gaps(wheels, default_max_wheel_gap_s(wheels));
  ASSERT_EQ(gaps.size(), 1u);
  EXPECT_EQ(gaps[0].sample, 50u);
  EXPECT_NEAR(gaps[0].duration_s, 1.02, 1e-9);
  break_chain_at_gaps(wheels, gaps);
  EXPECT_TRUE(wheels.breaks_at(50));
  EXPECT_FALSE(wheels.breaks_at(49));
  EXPECT_EQ(wheels.rev_rl[50], 0.0);
}

enum class GapKind { kCountsOfTheGap, kHeldRate };

// Removes `seconds` of wheel samples where the vehicle turns hardest in the middle third of the
// log; the sample after the gap gets what that kind of sensor would report.
Log with_gap_mid_turn(Log log, double seconds, GapKind kind) {
  WheelStream& w = log.wheels;
  std::size_t turn = w.size() / 3;
  double strongest = 0.0;
  for (std::size_t k = w.size() / 3; k < 2 * w.size() / 3; ++k) {
    const double yaw = std::abs(w.rev_rr[k] - w.rev_rl[k]);
    if (yaw > strongest) strongest = yaw, turn = k;
  }
  const std::size_t first = turn, removed = static_cast<std::size_t>(seconds / 0.02);
  const std::size_t after = first + removed;
  double rl = 0.0, rr = 0.0;
  for (std::size_t k = first; k <= after; ++k) rl += w.rev_rl[k], rr += w.rev_rr[k];
  if (kind == GapKind::kCountsOfTheGap) {
    w.rev_rl[after] = rl;
    w.rev_rr[after] = rr;
  } else {  // a speed sensor's last rate held over the whole gap
    w.rev_rl[after] *= static_cast<double>(removed + 1);
    w.rev_rr[after] *= static_cast<double>(removed + 1) * 1.2;  // and a noisy last sample
  }
  const auto erase = [&](std::vector<double>& v) {
    v.erase(v.begin() + static_cast<std::ptrdiff_t>(first),
            v.begin() + static_cast<std::ptrdiff_t>(after));
  };
  erase(w.t_s);
  erase(w.rev_rl);
  erase(w.rev_rr);
  return log;
}

class WheelGapCalibration : public ::testing::TestWithParam<GapKind> {
 protected:
  static void SetUpTestSuite() {
    clean_ = new Log(simulated_log(sim::simulate(experiments::worn_ideal_circuit(2, 1))));
  }
  static void TearDownTestSuite() { delete clean_; }
  static Log* clean_;
};
Log* WheelGapCalibration::clean_ = nullptr;

void expect_within_noise(const CalibrationSummary& gap, const CalibrationSummary& clean) {
  SCOPED_TRACE(gap.brief_report());
  EXPECT_TRUE(gap.usable()) << gap.message;
  EXPECT_EQ(gap.preparation.wheel_gaps.size(), 1u);
  EXPECT_NEAR(gap.preparation.wheel_gaps.at(0).duration_s, 1.52, 1e-6);
  EXPECT_LT(std::abs(gap.estimate.circumference_rl_m - clean.estimate.circumference_rl_m),
            clean.sigma_rl_m());
  EXPECT_LT(std::abs(gap.estimate.circumference_rr_m - clean.estimate.circumference_rr_m),
            clean.sigma_rr_m());
  EXPECT_NE(gap.brief_report(), "");
}

TEST_P(WheelGapCalibration, AGapMidTurnMovesTheEstimateByLessThanTheNoise) {
  const Log gap = with_gap_mid_turn(*clean_, 1.5, GetParam());
  const IterativeSummary clean_iterative = calibrate_iterative(*clean_);
  const IterativeSummary gap_iterative = calibrate_iterative(gap);
  expect_within_noise(gap_iterative, clean_iterative);
  EXPECT_NE(gap_iterative.full_report().find("1 gap(s) in the wheel stream (longest 1.52 s"),
            std::string::npos)
      << gap_iterative.full_report();
  expect_within_noise(calibrate_batch(gap), calibrate_batch(*clean_));
  expect_within_noise(calibrate_augmented(gap), calibrate_augmented(*clean_));
  // Without the break the held rate is integrated as motion: a phantom turn that ruins it.
  if (GetParam() == GapKind::kHeldRate) {
    CalibrationOptions no_breaks;
    no_breaks.max_wheel_gap_s = 1e4;
    const IterativeSummary integrated = calibrate_iterative(gap, {}, no_breaks);
    EXPECT_GT(std::abs(integrated.estimate.circumference_rr_m -
                       clean_iterative.estimate.circumference_rr_m),
              3.0 * clean_iterative.sigma_rr_m());
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, WheelGapCalibration,
                         ::testing::Values(GapKind::kCountsOfTheGap, GapKind::kHeldRate),
                         [](const ::testing::TestParamInfo<GapKind>& kind) {
                           return kind.param == GapKind::kCountsOfTheGap ? std::string("counts")
                                                                         : std::string("held_rate");
                         });

}  // namespace
}  // namespace odocal
