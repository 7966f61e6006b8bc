// docs/importing.md's "logger as it is", end to end: tools/make_messy_logger.py writes a simulated
// drive the way two real loggers would (deg/s wheel sensors, one mounted mirrored; two unrelated
// clocks, one 0.4 s off what the map knows; 5 Hz fixes repeated on 100 Hz rows with the IMU in g
// and deg/s; "sep=," lines and trailing commas), and examples/messy-logger/map.yaml with --sync
// imports it into the log the simulator wrote, without a script.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "../support/run_cli.hpp"
#include "odocal/io/log_reader.hpp"

namespace odocal::testing {
namespace {

namespace fs = std::filesystem;

TEST(MessyLogger, ImportsWithoutAScriptAndFindsTheClockError) {
  const fs::path dir = fs::temp_directory_path() / "odocal_messy_logger";
  fs::remove_all(dir);
  const std::string source = ODOCAL_SOURCE_DIR;
  ASSERT_EQ(std::system(fmt::format("/usr/bin/python3 {}/tools/make_messy_logger.py {} {}", source,
                                    ODOCAL_CLI_PATH_FOR_TESTS, (dir / "logger").string())
                            .c_str()),
            0);
  const std::string import =
      fmt::format("import csv --map {}/examples/messy-logger/map.yaml --in {} --out ", source,
                  (dir / "logger").string());
  const CliRun plain = run_cli(import + (dir / "plain").string());
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_NE(plain.out.find("gnss: 10670 repeated rows collapsed (dedupe)"), std::string::npos)
      << plain.out;
  // Without --sync the doctor names logger B's clock error; with it the import applies it.
  const CliRun doctor = run_cli("doctor " + (dir / "plain").string());
  EXPECT_EQ(doctor.status, 3);
  EXPECT_NE(doctor.out.find("time.gnss_offset"), std::string::npos) << doctor.out;
  const CliRun synced = run_cli(import + (dir / "synced").string() + " --sync");
  ASSERT_EQ(synced.status, 0) << synced.err;
  for (const char* file : {"gnss.csv", "imu.csv"}) {
    const auto at = synced.out.find(fmt::format("{}: clock moved by ", file));
    ASSERT_NE(at, std::string::npos) << synced.out;
    EXPECT_NEAR(std::stod(synced.out.substr(at + std::string(file).size() + 17)), -0.4, 0.02)
        << synced.out;
  }
  EXPECT_EQ(run_cli("doctor " + (dir / "synced").string()).status, 0);

  // The imported wheels are the simulator's: the mirrored sensor's sign and deg/s undone.
  const Log log = read_log(dir / "synced");
  double rl = 0, rr = 0;
  for (std::size_t k = 0; k < log.wheels.size(); ++k) {
    rl += log.wheels.rev_rl[k];
    rr += log.wheels.rev_rr[k];
  }
  const double c = log.vehicle.circumference_rl_m;
  EXPECT_GT(rr * c, 900.0);
  EXPECT_NEAR(rl / rr, 1.0, 0.02);
  EXPECT_EQ(log.gnss.size(), 562u);
  ASSERT_TRUE(log.imu);
  EXPECT_NEAR(log.imu->t_s.front(), 0.0, 0.02);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace odocal::testing
