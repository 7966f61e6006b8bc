// Simulating the default scenario: 3 laps of the built-in circuit with every sensor at 50 Hz
// (target: under 2 s, issue #3).

#include <benchmark/benchmark.h>

#include "odocal/io/scenario_io.hpp"
#include "odocal/sim/simulator.hpp"

namespace {

void BM_SimulateCircuitThreeLaps(benchmark::State& state) {
  const odocal::sim::Scenario scenario = odocal::load_scenario("circuit");
  for (auto _ : state) {
    odocal::sim::SimulatedDrive drive = odocal::sim::simulate(scenario);
    benchmark::DoNotOptimize(drive.truth.pose.back());
  }
}
BENCHMARK(BM_SimulateCircuitThreeLaps)->Unit(benchmark::kMillisecond);

}  // namespace
