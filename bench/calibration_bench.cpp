// Speed of the calibration's pieces on a 3-lap, 50 Hz log of the built-in circuit (30 754
// samples): one EKF pass (layer 2), one least-squares solve (layer 3), the layer-1 reference,
// and a whole calibration per method.

#include <benchmark/benchmark.h>

#include "odocal/estimation/calibration.hpp"
#include "odocal/estimation/circumference_ls.hpp"
#include "odocal/estimation/odometry_ekf.hpp"
#include "odocal/estimation/reference_filter.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace {

using namespace odocal;

const Log& three_lap_log() {
  static const Log log = [] {
    sim::Scenario scenario = load_scenario("circuit");
    scenario.ideal = true;
    scenario.vehicle.wear_rl_mm = 1.5;
    scenario.vehicle.wear_rr_mm = 1.0;
    return simulated_log(sim::simulate(scenario));
  }();
  return log;
}

void BM_ReferenceFilter(benchmark::State& state) {
  ReferenceOptions options;
  options.mode = state.range(0) == 0 ? ReferenceMode::kFilter : ReferenceMode::kSmoother;
  for (auto _ : state)
    benchmark::DoNotOptimize(compute_reference(three_lap_log(), options).poses.back());
  state.SetLabel(state.range(0) == 0 ? "filter" : "smoother");
}
BENCHMARK(BM_ReferenceFilter)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

void BM_OdometryEkfPass(benchmark::State& state) {
  const ReferenceTrajectory reference = compute_reference(three_lap_log());
  std::vector<Pose2> x_hat;
  for (auto _ : state) {
    run_odometry_ekf(three_lap_log().wheels, reference, three_lap_log().vehicle.nominal_params(),
                     {decaying_process_diagonal(3, 2.0), Eigen::Vector3d(1, 1, 0.01)}, x_hat);
    benchmark::DoNotOptimize(x_hat.back());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(reference.poses.size()));
}
BENCHMARK(BM_OdometryEkfPass)->Unit(benchmark::kMillisecond);

void BM_LeastSquaresSolve(benchmark::State& state) {
  const ReferenceTrajectory reference = compute_reference(three_lap_log());
  for (auto _ : state) {
    benchmark::DoNotOptimize(fit_circumferences(three_lap_log().wheels, reference, reference.poses,
                                                1.6, Eigen::Vector3d(1, 1, 10), 10));
  }
}
BENCHMARK(BM_LeastSquaresSolve)->Unit(benchmark::kMillisecond);

// The estimator alone: after the iterative, fixed-P and augmented methods the model-adequacy
// judge (a batch fit) is off here and measured by BM_CalibrateJudged.
void BM_Calibrate(benchmark::State& state) {
  CalibrationConfig options;
  options.method = static_cast<CalibrationMethod>(state.range(0));
  options.common.judge_model_adequacy = false;
  std::string label;
  for (auto _ : state) {
    const AnyCalibrationSummary summary = calibrate(three_lap_log(), options);
    label = std::string(method_name(options.method));
    if (const auto* iterative = std::get_if<IterativeSummary>(&summary)) {
      label += ", " + std::to_string(iterative->iterations.size()) + " iterations";
    } else if (const auto* batch = std::get_if<BatchSummary>(&summary);
               batch && batch->tyre_selection.compared) {
      // The default tyre_model auto fits the tyre models too: say what it kept after how many.
      const TyreModelSelection& selection = batch->tyre_selection;
      label += ", tyre_model auto: " +
               (selection.chosen == "none" ? std::string("plain") : selection.chosen) +
               " kept of " + std::to_string(1 + selection.candidates.size()) + " fits";
    }
  }
  state.SetLabel(label);
}
BENCHMARK(BM_Calibrate)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

// The batch with the paper's model alone (tyre_model none, the default until 2026-11-27),
// without the tyre models that judge it by default since 2026-11-29 (BM_CalibrateJudged measures
// the judge).
void BM_CalibrateBatchPlain(benchmark::State& state) {
  CalibrationConfig options;
  options.method = CalibrationMethod::kBatch;
  options.batch.tyre_model = TyreModelChoice::kNone;
  options.common.judge_model_adequacy = false;
  for (auto _ : state) benchmark::DoNotOptimize(core(calibrate(three_lap_log(), options)).usable());
}
BENCHMARK(BM_CalibrateBatchPlain)->Unit(benchmark::kMillisecond);

// The iterative method as `odocal calibrate` runs it by default: with the model-adequacy judge
// (a plain batch fit, then the tyre models' fits).
void BM_CalibrateJudged(benchmark::State& state) {
  CalibrationConfig options;
  for (auto _ : state) benchmark::DoNotOptimize(core(calibrate(three_lap_log(), options)).usable());
}
BENCHMARK(BM_CalibrateJudged)->Unit(benchmark::kMillisecond);

// The iterative method forced through all 30 iterations (no early stop), without the judge.
void BM_CalibrateThirtyIterations(benchmark::State& state) {
  IterativeOptions options;
  options.max_iterations = options.patience = 30;
  CalibrationOptions common;
  common.judge_model_adequacy = false;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        calibrate_iterative(three_lap_log(), options, common).iterations.size());
  }
}
BENCHMARK(BM_CalibrateThirtyIterations)->Unit(benchmark::kMillisecond);

}  // namespace
