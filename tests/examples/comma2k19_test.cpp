// A real car: the comma2k19 segment (../shared/data/real/comma2k19, skipped when absent)
// imported through examples/comma2k19/map.yaml and calibrated from GNSS + IMU + wheels. The
// test derives the true rear scale itself from the post-processed reference pose (distance
// along the reference path over the integrated rear wheel distance) and requires the
// calibration to match it within 0.2 %, and to refuse a left/right difference on this nearly
// straight road.

#include <gtest/gtest.h>

#include <filesystem>

#include "../support/temp_log_dir.hpp"
#include "estimation/doppler_scale.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/io/csv_import.hpp"
#include "odocal/io/log_reader.hpp"

namespace odocal {
namespace {

const std::filesystem::path kData =
    std::filesystem::path(ODOCAL_SOURCE_DIR) / "../shared/data/real/comma2k19";
const std::string kMap = std::string(ODOCAL_SOURCE_DIR) + "/examples/comma2k19/map.yaml";

// Reference path length over the rear wheels' integrated distance, on their common span.
double reference_scale(const Log& log) {
  const PoseStream& truth = *log.truth;
  const double begin = std::max(truth.t_s.front(), log.wheels.t_s.front());
  const double end = std::min(truth.t_s.back(), log.wheels.t_s.back());
  double path_m = 0.0;
  for (std::size_t k = 1; k < truth.size(); ++k) {
    if (truth.t_s[k - 1] >= begin && truth.t_s[k] <= end) {
      path_m += (truth.pose[k].head<2>() - truth.pose[k - 1].head<2>()).norm();
    }
  }
  // The same span of wheel distance, with the nominal circumferences the car used.
  const OdometryParams nominal = log.vehicle.nominal_params();
  double wheel_m = 0.0;
  const auto& first =
      *std::find_if(truth.t_s.begin(), truth.t_s.end(), [&](double t) { return t >= begin; });
  double last = first;
  for (double t : truth.t_s)
    if (t <= end) last = t;
  for (std::size_t k = 1; k < log.wheels.size(); ++k) {
    if (log.wheels.t_s[k - 1] >= first && log.wheels.t_s[k] <= last) {
      wheel_m += body_increment(log.wheels.increment(k), nominal).distance_m;
    }
  }
  return path_m / wheel_m;
}

TEST(Comma2k19, ImportedAndCalibratedScaleMatchesTheReferencePose) {
  if (!std::filesystem::exists(kData / "wheel_speeds.csv"))
    GTEST_SKIP() << "shared data absent: " << kData;
  const testing::TempLogDir out;
  const ImportSummary summary = import_csv(kMap, kData, out.path());
  EXPECT_NEAR(summary.wheel_distance_m, 1000.0, 20.0);
  const Log log = read_log(out.path());
  ASSERT_TRUE(log.truth.has_value());
  const double expected_scale = reference_scale(log);
  EXPECT_NEAR(expected_scale, 1.0085, 0.002);  // the data README: rear wheels ~0.85 % short

  LogReadOptions without_truth;
  without_truth.read_truth = false;
  const Log input = read_log(out.path(), without_truth);
  for (CalibrationMethod method : {CalibrationMethod::kIterative, CalibrationMethod::kFixedP}) {
    CalibrationConfig config;
    config.method = method;
    const CalibrationSummary result = core(calibrate(input, config));
    EXPECT_TRUE(result.usable()) << result.message;
    const double scale_rl = result.estimate.circumference_rl_m / result.nominal.circumference_rl_m;
    const double scale_rr = result.estimate.circumference_rr_m / result.nominal.circumference_rr_m;
    EXPECT_NEAR(scale_rl, expected_scale, 0.002 * expected_scale) << method_name(method);
    EXPECT_NEAR(scale_rr, expected_scale, 0.002 * expected_scale) << method_name(method);
    // Nearly straight: no confident left/right number.
    EXPECT_FALSE(result.difference_identifiable);
    EXPECT_NE(result.identifiability.find("not identifiable"), std::string::npos);
    EXPECT_DOUBLE_EQ(scale_rl, scale_rr);
  }
}

TEST(Comma2k19, TheReceiversDopplerSpeedHasTheScaleOfTheWheelsAndThePositions) {
  if (!std::filesystem::exists(kData / "wheel_speeds.csv"))
    GTEST_SKIP() << "shared data absent: " << kData;
  const testing::TempLogDir out;
  import_csv(kMap, kData, out.path());
  Log log = read_log(out.path());
  ASSERT_EQ(log.gnss.speed_mps.size(), log.gnss.size());
  const OdometryParams nominal = log.vehicle.nominal_params();
  const auto wheels = doppler_over_wheels(log, nominal);
  const auto positions = doppler_over_positions(log, nominal);
  ASSERT_TRUE(wheels && positions);
  // The rear wheels at their nominal circumference are ~0.85 % short (the reference pose's scale).
  EXPECT_NEAR(wheels->ratio, reference_scale(log), 0.005);
  EXPECT_NEAR(positions->ratio, 1.0, 0.02);
  EXPECT_NO_THROW(check_doppler_scale(log, nominal));
  // The same column in mph: refused, with its unit.
  for (double& v : log.gnss.speed_mps) v *= 2.2369;
  try {
    check_doppler_scale(log, nominal);
    ADD_FAILURE() << "a Doppler column in mph passed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mph"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace odocal
