// Simulating the default scenario: 3 laps of the built-in circuit with every sensor at 50 Hz
// (target: under 2 s, issue #3).

#include <benchmark/benchmark.h>

#include "odocal/io/scenario_io.hpp"
#include "odocal/sim/simulator.hpp"

namespace {

// Arg 0: --ideal (exact path); 1: the realistic vehicle (RK4 at 1 kHz, controllers at 100 Hz).
void BM_SimulateCircuitThreeLaps(benchmark::State& state) {
  odocal::sim::Scenario scenario = odocal::load_scenario("circuit");
  scenario.ideal = state.range(0) == 0;
  state.SetLabel(scenario.ideal ? "ideal" : "realistic");
  for (auto _ : state) {
    odocal::sim::SimulatedDrive drive = odocal::sim::simulate(scenario);
    benchmark::DoNotOptimize(drive.truth.pose.back());
  }
}
BENCHMARK(BM_SimulateCircuitThreeLaps)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
