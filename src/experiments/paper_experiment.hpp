#pragma once
// `odocal experiment paper`: every table and figure of the paper (Table 1 / Fig. 2, Figs. 4-7,
// Figs. 8-11, Fig. 12) in each simulator mode, with the Cramér–Rao bound of every run, plus the
// batch estimator beside them, under degraded GNSS and with its tyre model (issue 17). Results go
// to CSV/JSON under out_dir (layout in docs/results.md); tools/paper_report.py draws them.

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "experiments/paper_setup.hpp"

namespace odocal::experiments {

struct PaperExperimentOptions {
  std::filesystem::path out_dir = "paper";
  PaperSetup setup;
  int seeds = 10;  // Figs. 8-11
  std::vector<SimMode> modes{SimMode::kIdeal, SimMode::kRealistic};
  bool robustness = true;    // the degraded-GNSS runs (ideal mode only)
  bool tyre_models = true;   // the tyre model runs (both modes needed)
  bool fresh = false;        // recompute pieces that a previous run finished
  std::string command_line;  // recorded in experiment.json

  std::string validate() const;  // empty when valid
};

// Progress lines go to `progress`. Throws odocal::Error on invalid options or I/O failure.
void run_paper_experiment(const PaperExperimentOptions& options, std::FILE* progress);

}  // namespace odocal::experiments
