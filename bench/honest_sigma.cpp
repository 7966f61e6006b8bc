// Does the reported sigma cover the error when the configured GNSS noise is wrong? Monte Carlo
// over the built-in circuit (--ideal, 3 laps by default): the GNSS error is a first-order
// Gauss-Markov process (sigma 0.5-2 m, tau 10-120 s) on 5 cm of white noise, while the
// configuration claims 0.1 m of white noise and gnss.csv has no sigma_m. Each run is
// calibrated by the batch estimator with and without adapt_gnss_noise (and by the iterative
// method, for comparison); the share of errors inside 3 reported sigma is printed per method.
// Then clean runs (the paper's 3 m white GNSS, correctly configured) give the batch's reported
// sigma against the Cramér–Rao sigma, which must stay within 1.5x on every clean run (exit 1
// where it does not).
//
//   build/bench/odocal_honest_sigma [--runs 40] [--clean-runs 10] [--laps 3]
//                                   [--track-width-uncertainty 0.01]

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <array>
#include <cmath>
#include <vector>

#include "experiments/drifting_gnss.hpp"
#include "experiments/truth_comparison.hpp"
#include "experiments/worn_circuit.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

using namespace odocal;

namespace {

struct Coverage {
  int inside = 0, total = 0, usable = 0, runs = 0;
  double square_error_mm2 = 0.0, sigma_mm = 0.0, sigma_over_bound = 0.0;
  void add(const CalibrationSummary& s, const OdometryParams& truth, double bound_m) {
    ++runs;
    sigma_over_bound += std::hypot(s.sigma_rl_m(), s.sigma_rr_m()) / std::sqrt(2.0) / bound_m;
    usable += s.usable();
    const double errors[] = {s.estimate.circumference_rl_m - truth.circumference_rl_m,
                             s.estimate.circumference_rr_m - truth.circumference_rr_m};
    const double sigmas[] = {s.sigma_rl_m(), s.sigma_rr_m()};
    for (int w = 0; w < 2; ++w) {
      inside += std::abs(errors[w]) < 3.0 * sigmas[w];
      ++total;
      square_error_mm2 += 1e6 * errors[w] * errors[w];
      sigma_mm += 1e3 * sigmas[w];
    }
  }
  void print(const char* name) const {
    fmt::print("{:<28} {:>6.1f} % {:>10.3f} {:>12.3f} {:>12.2f} {:>9}/{}\n", name,
               100.0 * inside / total, std::sqrt(square_error_mm2 / total), sigma_mm / total,
               sigma_over_bound / runs, usable, runs);
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Coverage of the reported sigma under a wrongly configured GNSS noise"};
  int runs = 40, clean_runs = 10, laps = 3, only = 0;
  double track_width_uncertainty = BatchOptions{}.track_width_uncertainty;
  bool report = false;
  app.add_option("--runs", runs)->check(CLI::PositiveNumber);
  app.add_option("--clean-runs", clean_runs)->check(CLI::NonNegativeNumber);
  app.add_option("--laps", laps)->check(CLI::PositiveNumber);
  app.add_option("--only", only, "Run only this run number (1-based)");
  app.add_flag("--report", report,
               "Print each adapted batch's and the iterative method's full report");
  app.add_option("--track-width-uncertainty", track_width_uncertainty,
                 "The batch's track_width_uncertainty (what the held track's share scales with)")
      ->check(CLI::Range(0.0, 1.0));
  CLI11_PARSE(app, argc, argv);

  constexpr std::array<double, 3> kGmSigmas{0.5, 1.0, 2.0};
  constexpr std::array<double, 4> kGmTaus{10.0, 30.0, 60.0, 120.0};
  BatchOptions adapted, fixed;
  adapted.track_width_uncertainty = fixed.track_width_uncertainty = track_width_uncertainty;
  fixed.adapt_gnss_noise = false;
  Coverage batch_adapted, batch_fixed, iterative;
  for (int run = 0; run < runs; ++run) {
    if (only > 0 && run + 1 != only) continue;
    const double gm_sigma_m = kGmSigmas[static_cast<std::size_t>(run) % 3];
    const double gm_tau_s = kGmTaus[static_cast<std::size_t>(run / 3) % 4];
    const auto [scenario, drive, log, claimed] = experiments::drifting_gnss_drive(
        experiments::worn_ideal_circuit(laps, static_cast<std::uint64_t>(run + 1)), gm_sigma_m,
        gm_tau_s);
    const double bound = experiments::scenario_cramer_rao_bound(
                             scenario, simulated_log(drive, true), drive.true_params)
                             .rms_sigma_circumference_m();
    const BatchSummary a = calibrate_batch(log, adapted, claimed);
    batch_adapted.add(a, drive.true_params, bound);
    if (report) fmt::print(stderr, "{}Cramér–Rao sigma {:.3f} mm\n", a.full_report(), 1e3 * bound);
    batch_fixed.add(calibrate_batch(log, fixed, claimed), drive.true_params, bound);
    const IterativeSummary i = calibrate_iterative(log, {}, claimed);
    iterative.add(i, drive.true_params, bound);
    if (report) fmt::print(stderr, "{}", i.full_report());
    fmt::print(
        stderr,
        "run {:>2}: GM {:.1f} m, tau {:>3.0f} s -> error {:+.3f} / {:+.3f} mm, sigma "
        "{:.3f} mm, CRLB {:.3f} mm (estimated GM {:.2f} m, tau {:.0f} s; x{:.1f}; tyre model "
        "{}); iterative {:+.3f} mm at sigma {:.3f} mm\n",
        run + 1, scenario.gnss.gauss_markov_sigma_m, scenario.gnss.gauss_markov_tau_s,
        1e3 * (a.estimate.circumference_rl_m - drive.true_params.circumference_rl_m),
        1e3 * (a.estimate.circumference_rr_m - drive.true_params.circumference_rr_m),
        1e3 * a.sigma_rl_m(), 1e3 * bound, a.gnss_noise.gauss_markov_sigma_m,
        a.gnss_noise.gauss_markov_tau_s, a.gnss_noise.sigma_inflation, a.tyre_selection.chosen,
        1e3 * (i.estimate.circumference_rl_m - drive.true_params.circumference_rl_m),
        1e3 * i.sigma_rl_m());
  }
  fmt::print(
      "{} runs, {} laps of the built-in circuit (--ideal), GNSS: 5 cm white + Gauss-Markov "
      "(sigma 0.5/1/2 m, tau 10/30/60/120 s); configured: 0.1 m white\n",
      runs, laps);
  fmt::print("{:<28} {:>8} {:>10} {:>12} {:>12} {:>11}\n", "method", "in 3σ", "RMS mm", "mean σ mm",
             "σ / CRLB σ", "usable");
  batch_adapted.print("batch (adapt_gnss_noise)");
  batch_fixed.print("batch (configured noise)");
  iterative.print("iterative");

  if (clean_runs == 0) return 0;
  double ratio_sum = 0.0, worst = 0.0;
  int adapted_clean = 0;
  for (int run = 0; run < clean_runs; ++run) {
    const sim::Scenario scenario =
        experiments::worn_ideal_circuit(laps, static_cast<std::uint64_t>(run + 101));
    const sim::SimulatedDrive drive = sim::simulate(scenario);
    const Log log = simulated_log(drive, true);
    BatchOptions ideal;  // the experiments' ideal-mode wheel noise: the truth has no slip
    ideal.track_width_uncertainty = track_width_uncertainty;
    ideal.slip_sigma_m_per_sqrt_m = ideal.lateral_sigma_m_per_sqrt_m = 1e-6;
    const BatchSummary s = calibrate_batch(log, ideal);
    const double bound = experiments::scenario_cramer_rao_bound(scenario, log, drive.true_params)
                             .rms_sigma_circumference_m();
    const double reported = std::hypot(s.sigma_rl_m(), s.sigma_rr_m()) / std::sqrt(2.0);
    ratio_sum += reported / bound;
    worst = std::max(worst, reported / bound);
    adapted_clean += s.gnss_noise.adapted;
  }
  fmt::print(
      "clean runs ({}, the paper's 3 m white GNSS as configured): reported sigma / Cramér–Rao "
      "sigma mean {:.2f}, worst {:.2f}; noise adapted in {} runs\n",
      clean_runs, ratio_sum / clean_runs, worst, adapted_clean);
  // The target is said, not only the figure: a σ far above the bound on a clean log is no
  // failure of coverage, so nothing else here would show it (2026-12-07: 6.35x, unseen a day).
  constexpr double kTargetRatio = 1.5;
  const bool met = worst <= kTargetRatio;
  fmt::print("target: every clean run within {}x of the Cramér–Rao sigma: {}\n", kTargetRatio,
             met ? "met" : "NOT met");
  return met ? 0 : 1;
}
