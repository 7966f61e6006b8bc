// `odocal calibrate` and `odocal demo` end to end.

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "../support/run_cli.hpp"
#include "../support/temp_log_dir.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/vehicle_config_io.hpp"
#include "odocal/sim/scenario.hpp"

namespace odocal {
namespace {

using testing::read_text_file;
using testing::run_cli;
using testing::TempLogDir;

class CalibrateCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempLogDir();
    const auto run = run_cli(
        "simulate --scenario circuit --ideal --laps 1 --wear-rl 1.5 --wear-rr 1 --out " + log());
    ASSERT_EQ(run.status, 0) << run.err;
  }
  static void TearDownTestSuite() { delete dir_; }
  static std::string log() { return dir_->file("circuit"); }
  static TempLogDir* dir_;
};
TempLogDir* CalibrateCli::dir_ = nullptr;

TEST_F(CalibrateCli, PrintsAReportAndWritesJson) {
  const std::string json_file = dir_->file("result.json");
  const auto run = run_cli("calibrate " + log() + " --json " + json_file);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("method       iterative"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("mm from nominal"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("  before     mean"), std::string::npos) << run.out;
  const auto json = nlohmann::json::parse(read_text_file(json_file));
  for (const char* key :
       {"method", "circumference_rl_m", "circumference_rr_m", "chosen_iteration", "iterations",
        "dead_reckoning_before", "dead_reckoning_after", "configuration"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_EQ(json["method"], "iterative");
  EXPECT_EQ(json["termination"], "converged");
  EXPECT_EQ(json["usable"], true);
  EXPECT_NE(run.out.find("outcome      usable (converged)"), std::string::npos) << run.out;
  EXPECT_NEAR(json["circumference_rl_m"].get<double>(), 2 * M_PI * (0.3126 - 0.0015), 0.002);
  const auto& first = json["iterations"][0];
  for (const char* key : {"circumference_rl_m", "circumference_rr_m", "errors"})
    EXPECT_TRUE(first.contains(key));
  EXPECT_TRUE(first["errors"].contains("mean_position_m"));
  EXPECT_TRUE(first["errors"].contains("max_heading_deg"));
  EXPECT_EQ(json["configuration"]["measurement_diagonal"][2], 0.01);
}

TEST_F(CalibrateCli, ShowsTheDoctorsWarningsWithItsReport) {
  // A vehicle.yaml whose track is 9 % short of the one the wheels roll on: the doctor warns and
  // does not block, and calibrate shows the warning beside its report and in its JSON.
  const std::string copy = dir_->file("short-track");
  std::filesystem::copy(log(), copy, std::filesystem::copy_options::recursive);
  std::string vehicle = read_text_file(copy + "/vehicle.yaml");
  const std::size_t at = vehicle.find("track_width_m: ");
  ASSERT_NE(at, std::string::npos) << vehicle;
  vehicle.replace(at, vehicle.find('\n', at) - at, "track_width_m: 1.45");
  dir_->write("short-track/vehicle.yaml", vehicle);
  const std::string json_file = dir_->file("short-track.json");
  const auto run = run_cli("calibrate " + copy + " --json " + json_file);
  EXPECT_NE(run.out.find("doctor       [warning] the wheels roll on a track"), std::string::npos)
      << run.out;
  const auto json = nlohmann::json::parse(read_text_file(json_file));
  ASSERT_EQ(json["doctor_warnings"].size(), 1u) << json["doctor_warnings"];
  EXPECT_NE(json["doctor_warnings"][0].get<std::string>().find("(vehicle.track_width)"),
            std::string::npos);
  // The clean log: the doctor ran and warned of nothing; with --force it did not run.
  const auto clean = run_cli("calibrate " + log() + " --json " + json_file);
  ASSERT_EQ(clean.status, 0) << clean.err;
  EXPECT_EQ(clean.out.find("doctor "), std::string::npos) << clean.out;
  EXPECT_TRUE(nlohmann::json::parse(read_text_file(json_file))["doctor_warnings"].empty());
  ASSERT_EQ(run_cli("calibrate " + copy + " --force --json " + json_file).status, 0);
  EXPECT_FALSE(nlohmann::json::parse(read_text_file(json_file)).contains("doctor_warnings"));
}

TEST_F(CalibrateCli, OutputIsIdenticalWithoutTheTruthFiles) {
  const std::string copy = dir_->file("no-truth");
  std::filesystem::copy(log(), copy, std::filesystem::copy_options::recursive);
  std::filesystem::remove(copy + "/truth.csv");
  std::filesystem::remove(copy + "/truth.yaml");
  for (const char* method : {"iterative", "fixed-p", "augmented"}) {
    const auto with = run_cli(std::string("calibrate ") + log() + " --method " + method +
                              " --json " + dir_->file("a.json"));
    const auto without = run_cli(std::string("calibrate ") + copy + " --method " + method +
                                 " --json " + dir_->file("b.json"));
    ASSERT_EQ(with.status, 0) << with.err;
    EXPECT_TRUE(with.out == without.out) << method;
    EXPECT_TRUE(read_text_file(dir_->file("a.json")) == read_text_file(dir_->file("b.json")))
        << method;
  }
}

TEST_F(CalibrateCli, ConfigFileOverridesDefaultsAndBadKeysExitTwo) {
  dir_->write("config.yaml",
              "method: fixed-p\ndecay_exponent_q: 1.5\nreference: {mode: smoother}\n");
  const auto run = run_cli("calibrate " + log() + " --config " + dir_->file("config.yaml") +
                           " --json " + dir_->file("c.json"));
  ASSERT_EQ(run.status, 0) << run.err;
  const auto json = nlohmann::json::parse(read_text_file(dir_->file("c.json")));
  EXPECT_EQ(json["method"], "fixed-p");
  EXPECT_EQ(json["configuration"]["decay_exponent_q"], 1.5);
  EXPECT_EQ(json["configuration"]["reference"]["mode"], "smoother");

  dir_->write("bad.yaml", "decay_exponent_q: 3\n");
  const auto bad = run_cli("calibrate " + log() + " --config " + dir_->file("bad.yaml"));
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("bad.yaml:1: 'decay_exponent_q': 3 is out of range"), std::string::npos)
      << bad.err;
  dir_->write("typo.yaml", "reference:\n  gnss_sigma: 2\n");
  EXPECT_NE(run_cli("calibrate " + log() + " --config " + dir_->file("typo.yaml"))
                .err.find("'reference.gnss_sigma': unknown key"),
            std::string::npos);
}

TEST_F(CalibrateCli, PrintedConfigFedBackGivesTheSameResult) {
  const auto printed = run_cli("calibrate --method fixed-p --reference smoother --print-config");
  ASSERT_EQ(printed.status, 0) << printed.err;
  EXPECT_NE(printed.out.find("method: fixed-p"), std::string::npos) << printed.out;
  EXPECT_NE(printed.out.find("  mode: smoother"), std::string::npos) << printed.out;
  EXPECT_NE(printed.out.find("# m, 1e-06 to 10000: GNSS horizontal 1-sigma"), std::string::npos)
      << printed.out;
  dir_->write("printed.yaml", printed.out);
  const auto fed_back = run_cli("calibrate " + log() + " --config " + dir_->file("printed.yaml") +
                                " --json " + dir_->file("fed.json"));
  const auto direct = run_cli("calibrate " + log() + " --method fixed-p --reference smoother" +
                              " --json " + dir_->file("direct.json"));
  ASSERT_EQ(fed_back.status, 0) << fed_back.err;
  EXPECT_EQ(fed_back.out, direct.out);
  EXPECT_EQ(read_text_file(dir_->file("fed.json")), read_text_file(dir_->file("direct.json")));
}

TEST_F(CalibrateCli, AResultThatIsNotUsableExitsThreeWritesItsJsonButNoExports) {
  dir_->write("limit.yaml", "max_iterations: 1\n");
  const std::string vehicle = dir_->file("not-written.yaml");
  const auto run = run_cli("calibrate " + log() + " --config " + dir_->file("limit.yaml") +
                           " --json " + dir_->file("unusable.json") + " --vehicle-out " + vehicle);
  EXPECT_EQ(run.status, 3) << run.err;
  EXPECT_NE(run.err.find("odocal: not usable: the estimate still moved by"), std::string::npos)
      << run.err;
  EXPECT_NE(run.out.find("outcome      NOT USABLE (no_convergence)"), std::string::npos) << run.out;
  EXPECT_FALSE(std::filesystem::exists(vehicle));
  const auto json = nlohmann::json::parse(read_text_file(dir_->file("unusable.json")));
  EXPECT_EQ(json["usable"], false);
  EXPECT_EQ(json["termination"], "no_convergence");
  // validate refuses to use it.
  const auto validate = run_cli("validate " + log() + " --params " + dir_->file("unusable.json"));
  EXPECT_EQ(validate.status, 2);
  EXPECT_NE(validate.err.find("'usable': this calibration is not usable"), std::string::npos)
      << validate.err;
}

TEST_F(CalibrateCli, UnidentifiableLogExitsWithStatusThree) {
  const TempLogDir tiny;  // 3 m straight: far too short
  const auto run = run_cli("calibrate " + tiny.path().string());
  EXPECT_EQ(run.status, 3) << run.err;
  EXPECT_NE(run.err.find("odocal: cannot identify:"), std::string::npos) << run.err;
}

TEST(DemoCli, SimulatesCalibratesAndCompares) {
  const TempLogDir dir;
  const auto run = run_cli("demo --out " + dir.file("demo"));
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("nominal [m] estimate [m]     true [m] error [mm]"), std::string::npos)
      << run.out;
  EXPECT_TRUE(std::filesystem::exists(dir.file("demo") + "/wheels.csv"));
}

}  // namespace
}  // namespace odocal

namespace odocal {
namespace {

TEST(ImportCli, ImportsAndSummarisesOrExitsTwoOnABadMap) {
  const TempLogDir dir;
  dir.write("wheels_raw.csv", "time_ms,l,r\n0,0,0\n1000,48,48\n2000,96,96\n3000,144,144\n");
  dir.write("gps_raw.csv", "time_ms,e,n\n0,0,0\n1000,1,0\n2000,2,0\n3000,3,0\n");
  dir.write("map.yaml",
            "vehicle: {track_width_m: 1.6, circumference_rl_m: 2, circumference_rr_m: 2, "
            "ticks_per_rev: 96}\n"
            "streams:\n"
            "  wheels: {file: wheels_raw.csv, time: {column: time_ms, unit: ms}, rl: {column: l, "
            "unit: ticks},"
            " rr: {column: r, unit: ticks}}\n"
            "  gnss: {file: gps_raw.csv, time: {column: time_ms, unit: ms}, position: local,"
            " x: {column: e, unit: m}, y: {column: n, unit: m}}\n");
  const TempLogDir out;
  const auto run =
      run_cli("import csv --map " + dir.file("map.yaml") + " --out " + out.file("log"));
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("wheels          4          3.0"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("distance     3.0 m"), std::string::npos) << run.out;
  EXPECT_EQ(run_cli("deadreckon " + out.file("log") + " --start gnss").status, 0);

  // The logger's own directory, or one inside it, is never the output.
  for (const std::string& inside : {dir.path().string(), dir.file("log")}) {
    const auto refused = run_cli("import csv --map " + dir.file("map.yaml") + " --out " + inside);
    EXPECT_EQ(refused.status, 2) << inside;
    EXPECT_NE(refused.err.find("input directory"), std::string::npos) << refused.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("log")));

  dir.write(
      "bad.yaml",
      "vehicle: {track_width_m: 1.6, circumference_rl_m: 2, circumference_rr_m: 2}\nstreams: {}\n");
  const auto bad =
      run_cli("import csv --map " + dir.file("bad.yaml") + " --out " + out.file("log2"));
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.err.find("'streams.wheels': required stream is missing"), std::string::npos)
      << bad.err;
}

// An antenna 0.5 m left of the axle that vehicle.yaml does not state: the batch finds it in the
// fixes and the Doppler speed (detect_mounting), and the calibrated vehicle.yaml states it, so
// that layer 1 and the next calibration take it from there; validate's reference takes it from
// the result.
TEST(CalibrateCliAntenna, TheCalibratedVehicleYamlStatesTheAntennaWhereTheBatchFoundIt) {
  const TempLogDir dir;
  sim::Scenario scenario = load_scenario("urban");
  scenario.gnss.speed_sigma_mps = 0.05;
  scenario.gnss.lever_arm_y_m = 0.5;
  dir.write("urban-antenna.yaml", scenario_to_yaml(scenario));
  ASSERT_EQ(
      run_cli("simulate --scenario " + dir.file("urban-antenna.yaml") + " --out " + dir.file("log"))
          .status,
      0);
  const std::string vehicle = dir.file("calibrated.yaml");
  const std::string result = dir.file("result.json");
  const auto run = run_cli("calibrate " + dir.file("log") + " --method batch --vehicle-out " +
                           vehicle + " --json " + result);
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  const VehicleConfig calibrated = read_vehicle_config(vehicle);
  ASSERT_TRUE(calibrated.gnss_position_m) << read_text_file(vehicle);
  EXPECT_NEAR(calibrated.gnss_position_m->y(), 0.5, 0.05);
  EXPECT_NEAR(calibrated.gnss_position_m->x(), 0.0, 0.2);
  EXPECT_NE(run.out.find("mounting     the fit without them"), std::string::npos) << run.out;
  // validate takes the antenna from the result for its reference where vehicle.yaml states none.
  const auto validated = run_cli("validate " + dir.file("log") + " --params " + result);
  ASSERT_EQ(validated.status, 0) << validated.out << validated.err;
  EXPECT_NE(validated.out.find("antenna      the result's, "), std::string::npos) << validated.out;
  // Calibrated again from there, the antenna is held where it was found: nothing to look for.
  std::filesystem::copy_file(vehicle, dir.file("log/vehicle.yaml"),
                             std::filesystem::copy_options::overwrite_existing);
  const auto again = run_cli("calibrate " + dir.file("log") + " --method batch");
  ASSERT_EQ(again.status, 0) << again.out << again.err;
  EXPECT_EQ(again.out.find("mounting     the fit without them"), std::string::npos) << again.out;
}

}  // namespace
}  // namespace odocal
