// A real car: the comma2k19 segment (../shared/data/real/comma2k19, skipped when absent)
// imported through examples/comma2k19/map.yaml and calibrated from GNSS + IMU + wheels. The
// test derives the true rear scale itself from the post-processed reference pose (distance
// along the reference path over the integrated rear wheel distance) and requires the
// calibration to match it within 0.2 %, and to refuse a left/right difference on this nearly
// straight road.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "../support/temp_log_dir.hpp"
#include "estimation/batch_fit.hpp"
#include "estimation/doppler_scale.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/io/csv_import.hpp"
#include "odocal/io/log_reader.hpp"

namespace odocal {
namespace {

const std::filesystem::path kData =
    std::filesystem::path(ODOCAL_SOURCE_DIR) / "../shared/data/real/comma2k19";
const std::string kMap = std::string(ODOCAL_SOURCE_DIR) + "/examples/comma2k19/map.yaml";

// The segment imported through the example's map, as read back (the shared data must exist).
Log imported_log(const LogReadOptions& options = {}) {
  const testing::TempLogDir out;
  import_csv(kMap, kData, out.path());
  return read_log(out.path(), options);
}

// Reference path length over the rear wheels' integrated distance, on their common span.
// The reference pose's horizontal path over the wheels' distance in the same span, the wheels
// read `wheels_lead_s` earlier than the reference's clock says.
double reference_scale(const Log& log, double wheels_lead_s = 0.0) {
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
    if (log.wheels.t_s[k - 1] >= first - wheels_lead_s &&
        log.wheels.t_s[k] <= last - wheels_lead_s) {
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
  Log log = imported_log();
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

TEST(Comma2k19, TheWheelSpeedsLagIsFoundWhereAPhysicalFitReadsItAsSlip) {
  // The receiver's fixes are stamped ~0.1 s after the wheel speeds of the same moment (their
  // arrival on the phone's clock). Not estimated, the physical terms of a car that vehicle.yaml
  // states front-driven (its rear wheels roll free, so the lag can only be brake slip and load)
  // read it as brake slip, and the model check names the Doppler residual following a_x.
  // detect_latency (the default) fits the log again with the latency and takes it. The phone's
  // forward offset (0.7 m/s^2: it is pitched by 4 deg) is measured over the drive, which never
  // stops, and removed (drive_forward_offset.hpp): it is no longer carried whole in the sigma.
  if (!std::filesystem::exists(kData / "wheel_speeds.csv"))
    GTEST_SKIP() << "shared data absent: " << kData;
  Log log = imported_log();
  const Log with_truth = log;
  log.truth.reset();
  log.vehicle.body.drivetrain = Drivetrain::kFront;
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  options.detect_latency = false;
  const BatchSummary blind = calibrate_batch(log, options);
  ASSERT_EQ(blind.tyre_selection.chosen, "physical") << blind.full_report();
  ASSERT_TRUE(blind.preparation.drive_forward_offset.has_value()) << blind.full_report();
  EXPECT_TRUE(blind.preparation.drive_forward_offset->removed);
  EXPECT_NEAR(blind.preparation.drive_forward_offset->forward_mps2, -0.707, 0.05);
  EXPECT_LT(blind.forward_offset_sigma_mps2, 0.06);
  EXPECT_NE(blind.model_adequacy.verdict.find("longitudinal acceleration"), std::string::npos)
      << blind.full_report();

  options.detect_latency = true;
  const BatchSummary found = calibrate_batch(log, options);
  ASSERT_TRUE(found.latency_detection.has_value()) << found.full_report();
  EXPECT_TRUE(found.latency_detection->taken);
  EXPECT_NEAR(found.latency_detection->latency_s, 0.1, 0.03);
  // The reference's scale (its horizontal path over the wheels' 3-D distance, so lifted by the
  // 3-D path's excess) is known only as well as its own clock: between the wheels' clock and the
  // receiver's, 2.3 mm apart on this minute. The estimate lies within its 3 sigma of that span.
  const double nominal_m = log.vehicle.nominal_params().circumference_rl_m;
  const double lift = 1.0 + found.preparation.length_excess;
  const double on_wheels_clock_m = nominal_m * lift * reference_scale(with_truth);
  const double on_receivers_clock_m =
      nominal_m * lift * reference_scale(with_truth, found.latency_detection->latency_s);
  EXPECT_GT(found.estimate.circumference_rl_m,
            std::min(on_wheels_clock_m, on_receivers_clock_m) - 3.0 * found.sigma_rl_m())
      << found.full_report();
  EXPECT_LT(found.estimate.circumference_rl_m,
            std::max(on_wheels_clock_m, on_receivers_clock_m) + 3.0 * found.sigma_rl_m())
      << found.full_report();
}

TEST(Comma2k19, NoSlipCoefficientIsReportedBelowZero) {
  // A slip coefficient is an axle's share of the force over its slip stiffness. On this minute
  // (vehicle.yaml states no body: a driven rear axle is assumed) the phone's accelerometer puts a
  // few samples past the grip, where the slip is held; the brake slip then fitted at
  // -0.013 +- 0.006, which no tyre has and the log did not show: it is held at a car's value.
  if (!std::filesystem::exists(kData / "wheel_speeds.csv"))
    GTEST_SKIP() << "shared data absent: " << kData;
  LogReadOptions without_truth;
  without_truth.read_truth = false;
  const Log log = imported_log(without_truth);
  BatchOptions options;
  options.max_sigma_circumference_m = 0.01;
  const BatchSummary result = calibrate_batch(log, options);
  ASSERT_EQ(result.tyre_selection.chosen, "physical") << result.full_report();
  for (const EstimatedParameter& p : result.parameters) {
    if (p.name != "tyre_drive_slip" && p.name != "tyre_brake_slip") continue;
    EXPECT_TRUE(p.value >= 0.0 || std::abs(p.value) > 3.0 * p.sigma)
        << p.name << " " << p.value << " +- " << p.sigma << "\n"
        << result.full_report();
  }
}

TEST(Comma2k19, APlainFitCarriesItsGapToAPhysicalFitThatHoldsEveryCoefficient) {
  // With the latency estimated and vehicle.yaml's rear roll share at 0.1, the log identifies
  // none of the physical terms' coefficients: each is held at a car's value, and so held they fit
  // the minute decisively better than the plain model and put the circumferences at rest ~1 mm
  // from it. Such a fit cannot stand (nothing of it is the log's), and the plain fit stood at a
  // sigma of 0.14 mm without its gap; it now carries it. The held fit's gap was the phone's
  // forward offset's (0.7 m/s^2 taken for brake force): measured over the drive and removed, the
  // two agree within 0.14 mm, so it is left in here, as it was before the drive measured it.
  if (!std::filesystem::exists(kData / "wheel_speeds.csv"))
    GTEST_SKIP() << "shared data absent: " << kData;
  LogReadOptions without_truth;
  without_truth.read_truth = false;
  Log log = imported_log(without_truth);
  log.vehicle.body.rear_roll_share = 0.1;
  BatchOptions options;
  options.tyre_model = TyreModelChoice::kAuto;
  options.estimate_latency = true;
  options.max_sigma_circumference_m = 0.01;
  CalibrationOptions offset_left_in;
  offset_left_in.remove_accelerometer_offset = false;
  const BatchSummary result = calibrate_batch(log, options, offset_left_in);
  const TyreModelSelection& selection = result.tyre_selection;
  ASSERT_EQ(selection.chosen, "none") << result.full_report();
  ASSERT_FALSE(selection.candidates.empty());
  const TyreCandidate& physical = selection.candidates.front();
  ASSERT_EQ(physical.model, "physical");
  EXPECT_TRUE(physical.tyre);
  EXPECT_TRUE(physical.every_coefficient_held);
  EXPECT_LT(physical.bic, selection.plain_bic - batch::kDecisiveBic);
  EXPECT_EQ(selection.plain_gap_to, "physical") << result.full_report();
  EXPECT_NE(result.model_adequacy.verdict.find("identified none of its coefficients"),
            std::string::npos)
      << result.model_adequacy.verdict;

  // Unjudged, the plain fit's own sigma is a fraction of the gap.
  options.tyre_model = TyreModelChoice::kNone;
  CalibrationOptions unjudged = offset_left_in;
  unjudged.judge_model_adequacy = false;
  const BatchSummary plain = calibrate_batch(log, options, unjudged);
  const double gap_rl_m = std::abs(physical.circumference[0] - plain.estimate.circumference_rl_m);
  EXPECT_GT(gap_rl_m, 3.0 * plain.sigma_rl_m()) << plain.full_report();
  // Judged, it carries the gap: auto's answer is the plain one, its sigma covering the gap.
  EXPECT_DOUBLE_EQ(result.estimate.circumference_rl_m, plain.estimate.circumference_rl_m);
  EXPECT_GE(result.sigma_rl_m(), gap_rl_m);
}

TEST(Comma2k19, AForwardOffsetAddedToThePhonesIsMeasuredOverTheDriveAndTakenOut) {
  // The phone's own offset (-0.70 m/s^2, pitched by 4 deg) with 0.4 m/s^2 more, as
  // another mount would read: the drive (which never stops, its grade projected with the GNSS
  // altitude) measures the sum, and the calibration (the defaults: batch, tyre model auto) is
  // the unaltered log's. Without the altitude the open drive cannot tell the slope from the
  // offset: the sigma carries what driving straight reads, and the answer is refused.
  if (!std::filesystem::exists(kData / "wheel_speeds.csv"))
    GTEST_SKIP() << "shared data absent: " << kData;
  LogReadOptions without_truth;
  without_truth.read_truth = false;
  const Log log = imported_log(without_truth);
  const BatchSummary as_logged = calibrate_batch(log, BatchOptions{});
  ASSERT_TRUE(as_logged.usable()) << as_logged.full_report();
  ASSERT_TRUE(as_logged.preparation.drive_forward_offset.has_value());
  const double phones_mps2 = as_logged.preparation.drive_forward_offset->forward_mps2;
  constexpr double kAddedMps2 = 0.4;
  Log moved = log;
  for (double& ax : moved.imu->ax_mps2) ax += kAddedMps2;
  const BatchSummary result = calibrate_batch(moved, BatchOptions{});
  ASSERT_TRUE(result.preparation.drive_forward_offset.has_value()) << result.full_report();
  EXPECT_TRUE(result.preparation.drive_forward_offset->removed);
  EXPECT_NEAR(result.preparation.drive_forward_offset->forward_mps2, phones_mps2 + kAddedMps2,
              1e-3);
  EXPECT_TRUE(result.usable()) << result.full_report();
  EXPECT_NEAR(result.estimate.circumference_rl_m, as_logged.estimate.circumference_rl_m,
              0.05 * as_logged.sigma_rl_m());

  Log flat = log;
  flat.gnss.altitude_m.clear();
  const BatchSummary open = calibrate_batch(flat, BatchOptions{});
  EXPECT_FALSE(open.preparation.drive_forward_offset.has_value()) << open.full_report();
  ASSERT_TRUE(open.preparation.driving_forward_offset_mps2.has_value());
  EXPECT_NEAR(open.forward_offset_sigma_mps2,
              std::abs(*open.preparation.driving_forward_offset_mps2), 1e-12);
  EXPECT_FALSE(open.usable()) << open.full_report();
  EXPECT_LT(std::abs(open.estimate.circumference_rl_m - as_logged.estimate.circumference_rl_m),
            3.0 * open.sigma_rl_m());
}

}  // namespace
}  // namespace odocal
