#include "experiments/tyre_model_experiment.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "experiments/truth_comparison.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/drift_validation.hpp"
#include "odocal/estimation/driving_state.hpp"
#include "odocal/estimation/log_preparation.hpp"
#include "odocal/estimation/median.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal::experiments {
namespace {

constexpr TyreModelChoice kRealisticModels[] = {TyreModelChoice::kNone, TyreModelChoice::kExtended,
                                                TyreModelChoice::kPhysical, TyreModelChoice::kAuto};
constexpr sim::Drivetrain kDrivetrains[] = {sim::Drivetrain::kRear, sim::Drivetrain::kFront};

// The targets.
constexpr double kTargetMeanAbsErrorMm = 1.0;
constexpr double kTargetWithin3Sigma = 0.9;
constexpr double kTargetDeadReckoningOverIdeal = 3.0;
constexpr double kTargetUrbanDriftPercent = 0.3;
constexpr double kTargetIdealErrorChange = 0.05;
constexpr double kTargetSecondsExtended = 3.0;

// The driver who shares the grip with the turn and has a sedan's power (docs/simulator.md,
// "Driver"): the circuit's driver uses each bound on its own, and on Hockenheim that makes the
// car fishtail once a lap (docs/tyre-model.md, "The simulated driver's share").
constexpr double kSedanPowerWpkg = 80.0;  // 120 kW for 1500 kg

sim::Scenario with_grip_sharing_driver(sim::Scenario scenario) {
  scenario.driver.friction_ellipse = true;
  scenario.driver.max_power_wpkg = kSedanPowerWpkg;
  return scenario;
}

// An automotive-grade accelerometer (a stability control's, against the paper's 0.2 m/s^2): the
// physical terms take each sample's force from it, and its noise walks dead reckoning's heading
// (docs/tyre-model.md, "The accelerometer's noise in dead reckoning").
constexpr double kQuietAccelerometerMps2 = 0.05;

sim::Scenario with_quiet_accelerometer(sim::Scenario scenario) {
  scenario.imu.acc_sigma_mps2 = kQuietAccelerometerMps2;
  return scenario;
}

// The tyres' force from the car's bus (wheels.csv's drive_force_n) beside the accelerometer: the
// physical terms take it in place of the accelerometer's forward reading (docs/tyre-model.md,
// "The drive force"). Its noise per sample is a torque signal's (0.07 m/s^2 for 1500 kg).
constexpr double kDriveForceSigmaN = 100.0;

sim::Scenario with_drive_force(sim::Scenario scenario) {
  scenario.wheels.drive_force_sigma_n = kDriveForceSigmaN;
  return scenario;
}

const char* drivetrain_name(sim::Drivetrain drivetrain) {
  return drivetrain == sim::Drivetrain::kFront ? "front" : "rear";
}

CalibrationConfig batch_options(SimMode mode, TyreModelChoice model) {
  CalibrationConfig options = method_options(CalibrationMethod::kBatch, mode);
  options.batch.tyre_model = model;
  // The extended model's sigma (~1.4 mm on this drive) is above the default refusal threshold of
  // 1 mm: every estimate is scored here, usable or not.
  options.batch.max_sigma_circumference_m = 0.01;
  return options;
}

nlohmann::json run_json(const Log& log, const OdometryParams& truth,
                        const CalibrationConfig& options) {
  const MethodRun run = run_method(log, truth, options);
  nlohmann::json json = method_run_to_json(run);
  json["tyre_model_used"] = !core(run.result).tyre_model.plain();
  json["accelerometer_walk_deg"] = deg_from_rad(core(run.result).accelerometer_walk.heading_rad);
  return json;
}

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double v : values) sum += v;
  return values.empty() ? NAN : sum / static_cast<double>(values.size());
}

// Paired differences over the seeds: their mean and its standard error.
std::pair<double, double> mean_and_standard_error(const std::vector<double>& differences) {
  const double average = mean(differences);
  double squares = 0.0;
  for (const double d : differences) squares += (d - average) * (d - average);
  const double count = static_cast<double>(differences.size());
  const double spread = count > 1.0 ? std::sqrt(squares / (count - 1.0)) : 0.0;
  return {average, spread / std::sqrt(count)};
}

// One wheel's error and reported sigma in a run. JSON writes an infinite sigma (no covariance: a
// rank-deficient fit) as null; read back as infinite, it covers any error, as it says nothing.
struct WheelResult {
  double error_mm{};
  double sigma_mm{};
};
WheelResult wheel_result(const nlohmann::json& run, const std::string& wheel) {
  const nlohmann::json& reported = run.at("reported_sigma_" + wheel + "_mm");
  return {run.at("error_" + wheel + "_mm").get<double>(),
          reported.is_null() ? std::numeric_limits<double>::infinity() : reported.get<double>()};
}

// A run's mean |error| and mean reported sigma over the two wheels.
std::pair<double, double> run_error_and_sigma(const nlohmann::json& run) {
  double error = 0.0, sigma = 0.0;
  for (const char* wheel : {"rl", "rr"}) {
    const WheelResult result = wheel_result(run, wheel);
    error += 0.5 * std::abs(result.error_mm);
    sigma += 0.5 * result.sigma_mm;
  }
  return {error, sigma};
}

// The ideal runs, auto against none seed by seed: whether the targets' change of the mean error
// is more than 10 seeds resolve, and the sigma each reports beside it.
nlohmann::json ideal_auto_against_none(const std::vector<nlohmann::json>& none,
                                       const std::vector<nlohmann::json>& automatic) {
  std::vector<double> differences, none_sigma, auto_sigma;
  for (std::size_t i = 0; i < none.size() && i < automatic.size(); ++i) {
    const auto [none_error, none_s] = run_error_and_sigma(none[i]);
    const auto [auto_error, auto_s] = run_error_and_sigma(automatic[i]);
    differences.push_back(auto_error - none_error);
    none_sigma.push_back(none_s);
    auto_sigma.push_back(auto_s);
  }
  const auto [difference, standard_error] = mean_and_standard_error(differences);
  return {{"mean_abs_error_difference_mm", difference},
          {"difference_standard_error_mm", standard_error},
          {"none_mean_reported_sigma_mm", mean(none_sigma)},
          {"auto_mean_reported_sigma_mm", mean(auto_sigma)}};
}

// One configuration's runs over the seeds.
nlohmann::json row_summary(const std::vector<nlohmann::json>& runs) {
  std::vector<double> absolute, position, heading, seconds, walk;
  int inside = 0, with_model = 0;
  for (const nlohmann::json& run : runs) {
    for (const char* wheel : {"rl", "rr"}) {
      const WheelResult result = wheel_result(run, wheel);
      absolute.push_back(std::abs(result.error_mm));
      inside += std::abs(result.error_mm) <= 3.0 * result.sigma_mm;
    }
    position.push_back(run.at("dr_mean_position_m").get<double>());
    heading.push_back(run.at("dr_mean_heading_deg").get<double>());
    seconds.push_back(run.at("milliseconds").get<double>() / 1e3);
    walk.push_back(run.at("accelerometer_walk_deg").get<double>());
    with_model += run.at("tyre_model_used").get<bool>();
  }
  return {{"mean_abs_error_mm", mean(absolute)},
          {"max_abs_error_mm", *std::max_element(absolute.begin(), absolute.end())},
          {"within_3_reported_sigma",
           static_cast<double>(inside) / static_cast<double>(absolute.size())},
          {"mean_dr_position_m", mean(position)},
          {"mean_dr_heading_deg", mean(heading)},
          {"mean_accelerometer_walk_deg", mean(walk)},
          {"mean_seconds", mean(seconds)},
          {"max_seconds", *std::max_element(seconds.begin(), seconds.end())},
          {"runs_with_tyre_model", with_model},
          {"runs", runs.size()}};
}

nlohmann::json target(const std::string& what, double measured, double limit, bool met) {
  return {{"target", what}, {"measured", measured}, {"limit", limit}, {"met", met}};
}

// The three accuracy targets for one `auto` row: its mean error, its share inside 3
// reported sigma, and its dead reckoning over ideal_dr_m, the ideal mode's it is held to (named
// in the target by `ideal`).
void add_accuracy_targets(nlohmann::json& targets, const std::string& who,
                          const nlohmann::json& row, double ideal_dr_m, const std::string& ideal) {
  const double error = row.at("mean_abs_error_mm");
  const double inside = row.at("within_3_reported_sigma");
  const double dr = row.at("mean_dr_position_m");
  targets.push_back(target(who + "mean abs error [mm]", error, kTargetMeanAbsErrorMm,
                           error <= kTargetMeanAbsErrorMm));
  targets.push_back(target(who + "share inside 3 reported sigma", inside, kTargetWithin3Sigma,
                           inside >= kTargetWithin3Sigma));
  targets.push_back(target(who + "whole-log DR over " + ideal, dr / ideal_dr_m,
                           kTargetDeadReckoningOverIdeal,
                           dr <= kTargetDeadReckoningOverIdeal * ideal_dr_m));
}

}  // namespace

nlohmann::json run_tyre_model_seed(const PaperSetup& setup, std::uint64_t seed) {
  nlohmann::json result{{"seed", seed}};
  for (const sim::Drivetrain drivetrain : kDrivetrains) {
    sim::Scenario scenario = paper_scenario(setup, SimMode::kRealistic, seed);
    scenario.dynamics.drivetrain = drivetrain;
    const sim::SimulatedDrive drive = sim::simulate(scenario);
    const Log log = simulated_log(drive, true);
    for (const TyreModelChoice model : kRealisticModels)
      result["realistic"][drivetrain_name(drivetrain)][enum_name(model)] =
          run_json(log, drive.true_params, batch_options(SimMode::kRealistic, model));
    const sim::SimulatedDrive forced = sim::simulate(with_drive_force(scenario));
    result["realistic_drive_force"][drivetrain_name(drivetrain)]["auto"] =
        run_json(simulated_log(forced, true), forced.true_params,
                 batch_options(SimMode::kRealistic, TyreModelChoice::kAuto));
    const sim::SimulatedDrive gentler = sim::simulate(with_grip_sharing_driver(scenario));
    result["grip_sharing"][drivetrain_name(drivetrain)]["auto"] =
        run_json(simulated_log(gentler, true), gentler.true_params,
                 batch_options(SimMode::kRealistic, TyreModelChoice::kAuto));
    const sim::SimulatedDrive quiet =
        sim::simulate(with_quiet_accelerometer(with_grip_sharing_driver(scenario)));
    result["grip_sharing_quiet_accelerometer"][drivetrain_name(drivetrain)]["auto"] =
        run_json(simulated_log(quiet, true), quiet.true_params,
                 batch_options(SimMode::kRealistic, TyreModelChoice::kAuto));
  }
  const sim::SimulatedDrive ideal = sim::simulate(paper_scenario(setup, SimMode::kIdeal, seed));
  const Log ideal_log = simulated_log(ideal, true);
  for (const TyreModelChoice model : {TyreModelChoice::kNone, TyreModelChoice::kAuto})
    result["ideal"][enum_name(model)] =
        run_json(ideal_log, ideal.true_params, batch_options(SimMode::kIdeal, model));
  const sim::SimulatedDrive ideal_gentler =
      sim::simulate(with_grip_sharing_driver(paper_scenario(setup, SimMode::kIdeal, seed)));
  result["grip_sharing_ideal"]["none"] =
      run_json(simulated_log(ideal_gentler, true), ideal_gentler.true_params,
               batch_options(SimMode::kIdeal, TyreModelChoice::kNone));
  return result;
}

namespace {

// `odocal validate --params` as it runs: the prepared log and its smoothed reference, computed
// once per log; each parameter set with its own tyre model; 60 s windows starting every 10 s
// (steadier medians on a 5-minute drive than its four disjoint windows); the tick counts smoothed
// as `--tick-smoothing` says.
class UrbanValidation {
 public:
  explicit UrbanValidation(const Log& input) {
    common_.reference.mode = ReferenceMode::kSmoother;
    LogPreparation done;
    prepared_ = prepare_log(input, common_, done);
    log_ = prepared_ ? &*prepared_ : &input;
    reference_ = compute_reference(*log_, common_.reference, ReferenceCovariance::kKeep);
  }
  UrbanValidation(const UrbanValidation&) = delete;  // log_ may point into prepared_
  UrbanValidation& operator=(const UrbanValidation&) = delete;

  DriftValidation drift(const OdometryParams& calibrated, const TyreModel& tyre,
                        double tick_smoothing_s = kDefaultTickSmoothingS) const {
    const OdometryParams nominal = log_->vehicle.nominal_params();
    DriftValidationOptions windows;
    windows.step_s = 10.0;
    windows.tick_smoothing_s = tick_smoothing_s;
    return validate_drift(
        with_tyre_model(*log_, nominal, log_->vehicle.tyre_model.value_or(TyreModel{})),
        with_tyre_model(*log_, calibrated, tyre), reference_, nominal, calibrated, windows);
  }

 private:
  CalibrationOptions common_;
  std::optional<Log> prepared_;
  const Log* log_ = nullptr;  // prepared_, or the input where preparing changed nothing
  ReferenceTrajectory reference_;
};

}  // namespace

nlohmann::json run_urban_drift_seed(std::uint64_t seed) {
  sim::Scenario scenario = load_scenario("urban");
  scenario.seeds.noise = seed;
  const sim::SimulatedDrive drive = sim::simulate(scenario);
  const Log log = simulated_log(drive);
  CalibrationConfig options = method_options(CalibrationMethod::kBatch, SimMode::kRealistic);
  options.batch.tyre_model = TyreModelChoice::kAuto;
  const AnyCalibrationSummary result = calibrate(log, options);
  const CalibrationSummary& summary = core(result);
  const UrbanValidation realistic(log);
  const DriftValidation calibrated = realistic.drift(summary.estimate, summary.tyre_model);
  // What the metric gives with the true circumferences at rest: on this drive, and on the same
  // drive in ideal mode (no tyre effects: the reference's and the encoders' own noise).
  const DriftValidation truth = realistic.drift(drive.true_params, TyreModel{});
  // The same realistic drive (the same path, sensors and noise) with wheels that neither slip nor
  // change radius with load: what the metric gives where the two-wheel model is exact.
  sim::Scenario exact_wheels = scenario;
  exact_wheels.dynamics.longitudinal_slip = false;
  exact_wheels.dynamics.load_dependent_radius = false;
  const sim::SimulatedDrive exact_drive = sim::simulate(exact_wheels);
  const Log exact_log = simulated_log(exact_drive);
  const DriftValidation exact =
      UrbanValidation(exact_log).drift(exact_drive.true_params, TyreModel{});
  scenario.ideal = true;
  const sim::SimulatedDrive ideal = sim::simulate(scenario);
  const Log ideal_log = simulated_log(ideal);
  const UrbanValidation ideal_windows(ideal_log);
  const DriftValidation floor = ideal_windows.drift(ideal.true_params, TyreModel{});
  // The same with the encoders' counts as they are (`--tick-smoothing 0`).
  const DriftValidation raw_ticks = realistic.drift(summary.estimate, summary.tyre_model, 0.0);
  const DriftValidation raw_floor = ideal_windows.drift(ideal.true_params, TyreModel{}, 0.0);
  return {
      {"seed", seed},
      {"usable", summary.usable()},
      {"tyre_model_used", !summary.tyre_model.plain()},
      {"windows", calibrated.calibrated_statistics.windows},
      {"nominal_median_drift_percent", calibrated.nominal_statistics.median_drift_percent},
      {"calibrated_median_drift_percent", calibrated.calibrated_statistics.median_drift_percent},
      {"true_static_median_drift_percent", truth.calibrated_statistics.median_drift_percent},
      {"exact_wheels_median_drift_percent", exact.calibrated_statistics.median_drift_percent},
      {"reference_only_median_drift_percent", calibrated.reference->median_drift_percent},
      {"ideal_true_median_drift_percent", floor.calibrated_statistics.median_drift_percent},
      {"calibrated_raw_ticks_median_drift_percent",
       raw_ticks.calibrated_statistics.median_drift_percent},
      {"ideal_true_raw_ticks_median_drift_percent",
       raw_floor.calibrated_statistics.median_drift_percent}};
}

nlohmann::json summarise_tyre_models(const std::vector<nlohmann::json>& seeds,
                                     const std::vector<nlohmann::json>& urban) {
  if (seeds.empty() || urban.empty()) throw Error("no tyre model seeds to summarise");
  const auto runs = [&](const nlohmann::json::json_pointer& at) {
    std::vector<nlohmann::json> found;
    for (const nlohmann::json& seed : seeds) found.push_back(seed.at(at));
    return found;
  };
  nlohmann::json rows = nlohmann::json::array();
  nlohmann::json targets = nlohmann::json::array();
  const nlohmann::json ideal_none = row_summary(runs("/ideal/none"_json_pointer));
  const nlohmann::json ideal_auto = row_summary(runs("/ideal/auto"_json_pointer));
  const double ideal_dr = ideal_auto.at("mean_dr_position_m").get<double>();
  for (const sim::Drivetrain drivetrain : kDrivetrains) {
    for (const TyreModelChoice model : kRealisticModels) {
      nlohmann::json row = row_summary(runs(nlohmann::json::json_pointer(
          std::string("/realistic/") + drivetrain_name(drivetrain) + "/" + enum_name(model))));
      row["mode"] = "realistic";
      row["drivetrain"] = drivetrain_name(drivetrain);
      row["tyre_model"] = enum_name(model);
      if (model == TyreModelChoice::kAuto) {
        add_accuracy_targets(targets,
                             std::string(drivetrain_name(drivetrain)) + "-wheel drive, auto: ", row,
                             ideal_dr, "the ideal mode's");
      }
      if (model == TyreModelChoice::kExtended || model == TyreModelChoice::kPhysical) {
        const double seconds = row.at("max_seconds");
        targets.push_back(target(std::string(drivetrain_name(drivetrain)) + "-wheel drive, " +
                                     enum_name(model) + ": slowest batch [s]",
                                 seconds, kTargetSecondsExtended,
                                 seconds < kTargetSecondsExtended));
      }
      rows.push_back(row);
    }
  }
  // The same drives with the drive force column: beside the targets, which hold the paper's
  // sensors.
  for (const sim::Drivetrain drivetrain : kDrivetrains) {
    nlohmann::json row = row_summary(runs(nlohmann::json::json_pointer(
        std::string("/realistic_drive_force/") + drivetrain_name(drivetrain) + "/auto")));
    row["mode"] = fmt::format("realistic, drive force column ({:g} N)", kDriveForceSigmaN);
    row["drivetrain"] = drivetrain_name(drivetrain);
    row["tyre_model"] = "auto";
    row["dr_over_ideal"] = row.at("mean_dr_position_m").get<double>() / ideal_dr;
    rows.push_back(row);
  }
  for (const auto& [name, row] : {std::pair{"none", ideal_none}, std::pair{"auto", ideal_auto}}) {
    nlohmann::json r = row;
    r["mode"] = "ideal";
    r["drivetrain"] = "rear";
    r["tyre_model"] = name;
    rows.push_back(r);
  }
  // The same runs with the grip-sharing driver, scored against its own ideal mode.
  nlohmann::json gentler_ideal = row_summary(runs("/grip_sharing_ideal/none"_json_pointer));
  const double gentler_ideal_dr = gentler_ideal.at("mean_dr_position_m").get<double>();
  for (const sim::Drivetrain drivetrain : kDrivetrains) {
    nlohmann::json row = row_summary(runs(nlohmann::json::json_pointer(
        std::string("/grip_sharing/") + drivetrain_name(drivetrain) + "/auto")));
    row["mode"] = "realistic, grip-sharing driver";
    row["drivetrain"] = drivetrain_name(drivetrain);
    row["tyre_model"] = "auto";
    add_accuracy_targets(
        targets,
        std::string("grip-sharing driver, ") + drivetrain_name(drivetrain) + "-wheel drive, auto: ",
        row, gentler_ideal_dr, "its ideal mode's");
    rows.push_back(row);
  }
  // The same with an automotive-grade accelerometer: beside the targets, which hold the
  // scenario's.
  for (const sim::Drivetrain drivetrain : kDrivetrains) {
    nlohmann::json row = row_summary(
        runs(nlohmann::json::json_pointer(std::string("/grip_sharing_quiet_accelerometer/") +
                                          drivetrain_name(drivetrain) + "/auto")));
    row["mode"] = fmt::format("realistic, grip-sharing driver, {:g} m/s² accelerometer",
                              kQuietAccelerometerMps2);
    row["drivetrain"] = drivetrain_name(drivetrain);
    row["tyre_model"] = "auto";
    row["dr_over_ideal"] = row.at("mean_dr_position_m").get<double>() / gentler_ideal_dr;
    rows.push_back(row);
  }
  gentler_ideal["mode"] = "ideal, grip-sharing driver";
  gentler_ideal["drivetrain"] = "rear";
  gentler_ideal["tyre_model"] = "none";
  rows.push_back(gentler_ideal);

  const double plain_error = ideal_none.at("mean_abs_error_mm");
  const double auto_error = ideal_auto.at("mean_abs_error_mm");
  const int ideal_extended = ideal_auto.at("runs_with_tyre_model");
  targets.push_back(
      target("ideal, auto: runs that chose a tyre model", ideal_extended, 0, ideal_extended == 0));
  const double change = std::abs(auto_error - plain_error) / plain_error;
  targets.push_back(target("ideal, auto: change of the mean abs error against none", change,
                           kTargetIdealErrorChange, change <= kTargetIdealErrorChange));

  std::vector<double> nominal_drift, calibrated_drift, true_drift, exact_drift, reference_drift,
      floor_drift, raw_drift, raw_floor_drift;
  for (const nlohmann::json& seed : urban) {
    nominal_drift.push_back(seed.at("nominal_median_drift_percent"));
    calibrated_drift.push_back(seed.at("calibrated_median_drift_percent"));
    true_drift.push_back(seed.at("true_static_median_drift_percent"));
    exact_drift.push_back(seed.at("exact_wheels_median_drift_percent"));
    reference_drift.push_back(seed.at("reference_only_median_drift_percent"));
    floor_drift.push_back(seed.at("ideal_true_median_drift_percent"));
    raw_drift.push_back(seed.at("calibrated_raw_ticks_median_drift_percent"));
    raw_floor_drift.push_back(seed.at("ideal_true_raw_ticks_median_drift_percent"));
  }
  // The calibration's own share, seed by seed against the same drive with exact wheels: the mean
  // difference and its standard error (the seeds' medians scatter by several hundredths each).
  std::vector<double> differences;
  for (std::size_t i = 0; i < calibrated_drift.size(); ++i)
    differences.push_back(calibrated_drift[i] - exact_drift[i]);
  const auto [mean_difference, difference_standard_error] = mean_and_standard_error(differences);
  const double urban_drift = median(calibrated_drift);
  targets.push_back(target("urban, auto: held-out median drift [%]", urban_drift,
                           kTargetUrbanDriftPercent, urban_drift <= kTargetUrbanDriftPercent));
  return {{"seeds", seeds.size()},
          {"rows", rows},
          {"urban",
           {{"seeds", urban.size()},
            {"nominal_median_drift_percent", median(nominal_drift)},
            {"calibrated_median_drift_percent", urban_drift},
            {"true_static_median_drift_percent", median(true_drift)},
            {"exact_wheels_median_drift_percent", median(exact_drift)},
            {"reference_only_median_drift_percent", median(reference_drift)},
            {"calibrated_minus_exact_wheels_mean_percent", mean_difference},
            {"calibrated_minus_exact_wheels_standard_error_percent", difference_standard_error},
            {"ideal_true_median_drift_percent", median(floor_drift)},
            {"calibrated_raw_ticks_median_drift_percent", median(raw_drift)},
            {"ideal_true_raw_ticks_median_drift_percent", median(raw_floor_drift)},
            {"runs", urban}}},
          {"ideal_auto_against_none", ideal_auto_against_none(runs("/ideal/none"_json_pointer),
                                                              runs("/ideal/auto"_json_pointer))},
          {"targets", targets}};
}

}  // namespace odocal::experiments
