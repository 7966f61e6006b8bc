// The whole pipeline on a fuzzed log: wheels.csv, gnss.csv and optionally imu.csv (parts of the
// input separated by a line "#--") with a fixed vehicle.yaml; read, dead-reckoned and calibrated
// by the iterative and the augmented method. Bad input ends in an odocal::Error; a result called
// usable has finite circumferences inside the plausible band, and dead reckoning is finite.
//
// The model judgement (batch fits of the same log) is 99 % of a unit's time under the fuzz build:
// a 7 KB log calibrates in 0.17 s without it and 18 s with it after both methods. It runs after
// the iterative method on inputs of even length, half of them, so that the mutations get runs.

#include <cmath>

#include "fuzz_support.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/estimation/dead_reckoning.hpp"
#include "odocal/io/log_reader.hpp"

namespace {

using namespace odocal;
namespace fs = std::filesystem;

void check_usable(const CalibrationSummary& summary, const CalibrationOptions& options) {
  if (!summary.usable()) return;
  for (const double c : {summary.estimate.circumference_rl_m, summary.estimate.circumference_rr_m})
    fuzz::require(std::isfinite(c) && std::abs(c / 1.96 - 1.0) <= options.max_relative_change);
  fuzz::require(std::isfinite(summary.sigma_rl_m()) && std::isfinite(summary.sigma_rr_m()));
}

void run(const fs::path& log_dir, bool judge) {
  LogReadOptions read_options;
  read_options.read_truth = false;
  const Log log = read_log(log_dir, read_options);
  const PoseStream path = dead_reckon(log.wheels, log.vehicle.nominal_params(), Pose2::Zero());
  for (const Pose2& pose : path.pose) fuzz::require(pose.allFinite());

  CalibrationConfig config;
  config.iterative.max_iterations = 3;
  config.iterative.patience = 1;
  for (const CalibrationMethod method :
       {CalibrationMethod::kIterative, CalibrationMethod::kAugmented}) {
    config.method = method;
    config.common.judge_model_adequacy = judge && method == CalibrationMethod::kIterative;
    fuzz::expect_only_odocal_errors(
        [&] { check_usable(core(calibrate(log, config)), config.common); });
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto parts = fuzz::split_parts(fuzz::as_text(data, size), 3);
  if (parts.size() < 2) return 0;
  const fs::path dir = fuzz::scratch_directory() / "log";
  fs::create_directories(dir);
  fuzz::write_file(dir / "vehicle.yaml",
                   "track_width_m: 1.6\ncircumference_rl_m: 1.96\ncircumference_rr_m: 1.96\n"
                   "ticks_per_rev: 96\ncounter_bits: 16\n");
  fuzz::write_file(dir / "wheels.csv", parts[0]);
  fuzz::write_file(dir / "gnss.csv", parts[1]);
  std::error_code ignored;
  fs::remove(dir / "imu.csv", ignored);
  if (parts.size() > 2) fuzz::write_file(dir / "imu.csv", parts[2]);
  fuzz::expect_only_odocal_errors([&] { run(dir, size % 2 == 0); });
  return 0;
}
