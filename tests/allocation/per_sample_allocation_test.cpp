// The calibration's loops must not allocate per sample (issue #4): every buffer is sized once
// per call or per iteration. This executable replaces the global operator new with a counting
// one and checks that a calibration of a log twice as long makes exactly as many allocations:
// a per-sample allocation, or a vector grown by push_back without a reserve, would add more.
// (Eigen's dynamic matrices bypass operator new; the per-sample loops use fixed-size types.)

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <string>

#include "odocal/estimation/calibration.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace {
std::atomic<long> allocations{0};
}  // namespace

void* operator new(std::size_t bytes) {
  allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* memory = std::malloc(bytes == 0 ? 1 : bytes)) return memory;
  throw std::bad_alloc();
}
// std::stable_sort's scratch buffer comes from the nothrow form: replace it too, so every
// allocation is counted and every pointer the deletes see came from malloc.
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept {
  allocations.fetch_add(1, std::memory_order_relaxed);
  return std::malloc(bytes == 0 ? 1 : bytes);
}
void operator delete(void* memory) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t) noexcept { std::free(memory); }
void operator delete(void* memory, const std::nothrow_t&) noexcept { std::free(memory); }
void* operator new[](std::size_t bytes) { return operator new(bytes); }
void operator delete[](void* memory) noexcept { std::free(memory); }
void operator delete[](void* memory, std::size_t) noexcept { std::free(memory); }

namespace odocal {
namespace {

Log circuit_log(int laps) {
  sim::Scenario scenario = load_scenario("circuit");
  scenario.ideal = true;
  scenario.route.laps = laps;
  scenario.vehicle.wear_rl_mm = 1.5;
  scenario.vehicle.wear_rr_mm = 1.0;
  return simulated_log(sim::simulate(scenario));
}

long allocations_of_calibration(const Log& log, const CalibrationConfig& options) {
  const long before = allocations.load();
  const AnyCalibrationSummary result = calibrate(log, options);
  const long during = allocations.load() - before;
  // The augmented KF is one filter pass, no loop.
  const auto* iterative = std::get_if<IterativeSummary>(&result);
  const bool loops = options.method != CalibrationMethod::kAugmented;
  EXPECT_EQ(iterative ? iterative->iterations.size() : 0,
            loops ? static_cast<std::size_t>(options.iterative.max_iterations) : 0);
  return during;
}

class PerSampleAllocation : public testing::TestWithParam<CalibrationMethod> {};

TEST_P(PerSampleAllocation, DoublingTheLogAddsNoAllocation) {
  CalibrationConfig options;
  options.method = GetParam();
  // Every method through the same number of iterations on both logs (the stop rule off).
  options.iterative.max_iterations = options.iterative.patience = 8;
  // The model-adequacy judge after the method is a batch solve: it allocates per keyframe, as
  // the batch does, outside the methods' per-sample loops.
  options.common.judge_model_adequacy = false;
  const Log one_lap = circuit_log(1), two_laps = circuit_log(2);
  ASSERT_GT(two_laps.wheels.size(), one_lap.wheels.size() * 19 / 10);
  const long short_log = allocations_of_calibration(one_lap, options);
  const long long_log = allocations_of_calibration(two_laps, options);
  EXPECT_GT(short_log, 0);  // the counter does see the library's allocations
  EXPECT_EQ(long_log, short_log);
}

INSTANTIATE_TEST_SUITE_P(Methods, PerSampleAllocation,
                         testing::Values(CalibrationMethod::kIterative, CalibrationMethod::kFixedP,
                                         CalibrationMethod::kAugmented),
                         [](const testing::TestParamInfo<CalibrationMethod>& method) {
                           std::string name = method_name(method.param);
                           std::erase(name, '-');
                           return name;
                         });

}  // namespace
}  // namespace odocal
