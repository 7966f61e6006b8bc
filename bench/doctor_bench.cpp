// odocal doctor on the default 3-lap circuit log (13.6 km, every sensor at 50 Hz), in memory:
// issue 16 asks for "well under a second".

#include <benchmark/benchmark.h>

#include "odocal/estimation/log_diagnosis.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace {

void BM_DoctorCircuitThreeLaps(benchmark::State& state) {
  const odocal::sim::Scenario scenario = odocal::load_scenario("circuit");
  const odocal::Log log = odocal::simulated_log(odocal::sim::simulate(scenario));
  for (auto _ : state) {
    odocal::Diagnosis diagnosis = odocal::diagnose_log(log);
    benchmark::DoNotOptimize(diagnosis.findings.size());
  }
}
BENCHMARK(BM_DoctorCircuitThreeLaps)->Unit(benchmark::kMillisecond);

}  // namespace
