// The Monte-Carlo summary against hand-computed statistics, and the piece cache's reuse rules.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "experiments/monte_carlo.hpp"
#include "experiments/piece_cache.hpp"

namespace odocal::experiments {
namespace {

nlohmann::json method_run(double error_rl, double error_rr, double sigma) {
  return {{"error_rl_mm", error_rl},       {"error_rr_mm", error_rr},
          {"reported_sigma_rl_mm", sigma}, {"reported_sigma_rr_mm", sigma},
          {"dr_mean_position_m", 2.0},     {"dr_mean_heading_deg", 0.5},
          {"milliseconds", 10.0}};
}

nlohmann::json seed(int n, double error_rl, double error_rr, double crlb_rl, double crlb_rr) {
  nlohmann::json methods;
  for (const char* name : {"iterative", "fixed-p", "augmented", "batch"})
    methods[name] = method_run(error_rl, error_rr, 0.5);
  return {{"seed", n},
          {"crlb_sigma_rl_mm", crlb_rl},
          {"crlb_sigma_rr_mm", crlb_rr},
          {"crlb_exact_counts_sigma_rl_mm", crlb_rl / 3.0},
          {"crlb_exact_counts_sigma_rr_mm", crlb_rr / 3.0},
          {"methods", methods}};
}

TEST(MonteCarloSummary, MatchesHandComputedStatistics) {
  // Errors (mm): seed 1: +1, -2; seed 2: +3, +0. CRLB sigma (mm): 0.1, 0.2 and 0.3, 0.4.
  const nlohmann::json summary =
      summarise_monte_carlo({seed(1, 1.0, -2.0, 0.1, 0.2), seed(2, 3.0, 0.0, 0.3, 0.4)});
  ASSERT_EQ(summary.size(), 4u);
  EXPECT_TRUE(summary[3]["paper_mean_abs_error_mm"].is_null());  // not in the paper
  const nlohmann::json& row = summary[0];
  EXPECT_EQ(row["method"], "iterative");
  EXPECT_EQ(row["seeds"], 2);
  EXPECT_DOUBLE_EQ(row["mean_abs_error_rl_mm"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(row["mean_abs_error_rr_mm"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(row["mean_abs_error_mm"].get<double>(), 1.5);
  EXPECT_DOUBLE_EQ(row["max_abs_error_mm"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(row["mean_error_mm"].get<double>(), 0.5);
  const double rms = std::sqrt((1.0 + 4.0 + 9.0 + 0.0) / 4.0);
  const double crlb = std::sqrt((0.01 + 0.04 + 0.09 + 0.16) / 4.0);
  EXPECT_DOUBLE_EQ(row["rms_error_mm"].get<double>(), rms);
  EXPECT_DOUBLE_EQ(row["crlb_sigma_mm"].get<double>(), crlb);
  EXPECT_DOUBLE_EQ(row["rms_over_crlb"].get<double>(), rms / crlb);
  EXPECT_NEAR(row["crlb_exact_counts_sigma_mm"].get<double>(), crlb / 3.0, 1e-15);
  // 3 sigma = 1.5 mm: |1| and |0| inside, |-2| and |3| outside.
  EXPECT_DOUBLE_EQ(row["within_3_reported_sigma"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(row["mean_dr_position_m"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(row["paper_mean_abs_error_mm"].get<double>(), 0.86);
  EXPECT_THROW(summarise_monte_carlo({}), std::exception);
}

TEST(PieceCache, ReusesOnlyAFinishedPieceWithTheSameStamp) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "odocal-piece-cache-test";
  std::filesystem::remove_all(dir);
  const PieceCache cache(false);
  EXPECT_FALSE(cache.reusable(dir, "config A"));
  cache.open(dir);
  EXPECT_FALSE(cache.reusable(dir, "config A"));  // opened, not finished
  cache.mark_done(dir, "config A");
  EXPECT_TRUE(cache.reusable(dir, "config A"));
  EXPECT_FALSE(cache.reusable(dir, "config B"));
  EXPECT_FALSE(PieceCache(true).reusable(dir, "config A"));  // --fresh
  cache.open(dir);  // recomputing drops the old stamp first
  EXPECT_FALSE(cache.reusable(dir, "config A"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace odocal::experiments
