// `odocal experiment paper` end to end on the built-in circuit, ideal mode, one seed: the files
// the plotting script reads, physically sensible numbers, and reuse on a re-run.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../support/run_cli.hpp"
#include "../support/temp_log_dir.hpp"

namespace odocal {
namespace {

using testing::read_text_file;
using testing::run_cli;

std::vector<std::vector<double>> read_numeric_csv(const std::string& path) {
  std::istringstream text(read_text_file(path));
  std::string line;
  std::getline(text, line);  // header
  std::vector<std::vector<double>> rows;
  while (std::getline(text, line)) {
    std::vector<double> row;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

TEST(ExperimentCli, ReproducesThePaperPiecesAndReusesThem) {
  testing::TempLogDir dir;
  const std::string out = dir.file("paper");
  const std::string command = "experiment paper --seeds 1 --laps 1 --modes ideal --out " + out;
  const auto run = run_cli(command);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.err.find("[  3/4] Figs. 8-11, Monte Carlo, ideal: seed 1/1"), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("[  4/4] degraded GNSS, batch vs iterative: seed 1/1"), std::string::npos)
      << run.err;

  // Table 1: no wear, no error beyond quantisation; equal wear grows the error; the paper's
  // most unequal pair is the worst.
  const auto table = read_numeric_csv(out + "/table1/ideal/table1.csv");
  ASSERT_EQ(table.size(), 7u);
  EXPECT_LT(table[0][2], 0.1);
  EXPECT_LT(table[1][2], table[2][2]);
  EXPECT_LT(table[2][2], table[3][2]);
  EXPECT_GT(table[6][2], table[5][2]);
  EXPECT_GT(table[6][2], 10.0);

  const auto single = nlohmann::json::parse(read_text_file(out + "/single/ideal/summary.json"));
  EXPECT_GT(single["crlb_sigma_rl_mm"].get<double>(), 0.0);
  EXPECT_LT(single["crlb_sigma_rl_mm"].get<double>(), 0.3);  // one lap: ~0.13 mm
  for (const char* method : {"iterative", "fixed-p", "augmented"})
    EXPECT_LT(std::abs(single["methods"][method]["error_rl_mm"].get<double>()), 1.0) << method;
  const auto iterations = read_text_file(out + "/single/ideal/iterations.csv");
  EXPECT_NE(iterations.find("\niterative,30,"), std::string::npos);  // run on for the plot
  EXPECT_NE(iterations.find("\nfixed-p,30,"), std::string::npos);
  for (const char* file : {"speed.csv", "path.csv", "gnss.csv", "augmented.csv"})
    EXPECT_TRUE(std::filesystem::file_size(out + "/single/ideal/" + file) > 100) << file;

  const auto summary =
      nlohmann::json::parse(read_text_file(out + "/monte_carlo/ideal/summary.json"));
  ASSERT_EQ(summary.size(), 4u);  // the paper's three methods and the batch estimator
  EXPECT_GT(summary[0]["rms_over_crlb"].get<double>(), 1.0);  // nobody beats the bound here
  EXPECT_TRUE(nlohmann::json::parse(read_text_file(out + "/experiment.json")).contains("date"));
  const auto robust = nlohmann::json::parse(read_text_file(out + "/robustness/summary.json"));
  ASSERT_EQ(robust["rows"].size(), 3u);
  EXPECT_EQ(robust["rows"][1]["gnss"], "degraded");

  const auto again = run_cli(command);
  ASSERT_EQ(again.status, 0) << again.err;
  EXPECT_NE(again.err.find("4 pieces reused"), std::string::npos) << again.err;
}

TEST(ExperimentCli, RejectsAMissingTrackFile) {
  const auto run = run_cli("experiment paper --track /nonexistent/track.csv --out /tmp/x");
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("/nonexistent/track.csv"), std::string::npos) << run.err;
}

}  // namespace
}  // namespace odocal
