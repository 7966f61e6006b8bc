// Dead reckoning throughput (wheel samples per second): the inner loop of every estimator that
// re-simulates the whole log (paper section 4).

#include <benchmark/benchmark.h>

#include <cmath>

#include "odocal/estimation/dead_reckoning.hpp"

namespace {

// A 3-lap, 50 Hz stand-in: 25 minutes of weaving motion.
odocal::WheelStream weaving_wheels(std::size_t samples) {
  odocal::WheelStream wheels;
  for (std::size_t k = 0; k < samples; ++k) {
    const double t = 0.02 * static_cast<double>(k);
    wheels.t_s.push_back(t);
    wheels.rev_rl.push_back(k == 0 ? 0.0 : 0.3 + 0.01 * std::sin(0.05 * t));
    wheels.rev_rr.push_back(k == 0 ? 0.0 : 0.3 - 0.01 * std::sin(0.05 * t));
  }
  return wheels;
}

void BM_DeadReckonWholeLog(benchmark::State& state) {
  const odocal::WheelStream wheels = weaving_wheels(static_cast<std::size_t>(state.range(0)));
  const odocal::OdometryParams params{1.964, 1.962, 1.6};
  for (auto _ : state) {
    odocal::PoseStream trajectory = odocal::dead_reckon(wheels, params, odocal::Pose2::Zero());
    benchmark::DoNotOptimize(trajectory.pose.back());
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));  // items = wheel samples
}
BENCHMARK(BM_DeadReckonWholeLog)->Arg(75'000)->Unit(benchmark::kMillisecond);

}  // namespace
