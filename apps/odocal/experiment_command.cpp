#include "experiment_command.hpp"

#include <fmt/format.h>

#include <memory>

#include "experiments/paper_experiment.hpp"
#include "number_checks.hpp"

namespace odocal::cli {
namespace {

struct ExperimentArgs {
  experiments::PaperExperimentOptions options;
  std::string track;
  std::vector<std::string> modes{"ideal", "realistic"};
};

void run_paper(ExperimentArgs& args) {
  if (!args.track.empty()) args.options.setup.track_csv = args.track;
  args.options.modes.clear();
  for (const std::string& mode : args.modes) {
    args.options.modes.push_back(*parse_enum<experiments::SimMode>(mode));
  }
  experiments::run_paper_experiment(args.options, stderr);
}

}  // namespace

void add_experiment_command(CLI::App& app, int argc, char** argv) {
  auto args = std::make_shared<ExperimentArgs>();
  for (int i = 0; i < argc; ++i)
    args->options.command_line += (i == 0 ? "odocal" : fmt::format(" {}", argv[i]));
  CLI::App* experiment =
      app.add_subcommand("experiment", "Reproduce the paper's experiments on the simulator");
  experiment->require_subcommand(1);
  CLI::App* paper = experiment->add_subcommand(
      "paper",
      "Table 1 / Fig. 2, Figs. 4-12 in the ideal and realistic simulator modes, with the "
      "Cramér-Rao bound of every run; CSV/JSON results for tools/paper_report.py");
  paper->add_option("--out", args->options.out_dir, "Results directory")->capture_default_str();
  paper
      ->add_option("--track", args->track,
                   "TUMFTM centreline CSV for the section 5 runs (Hockenheim); default: the "
                   "built-in circuit")
      ->check(CLI::ExistingFile);
  paper->add_option("--seeds", args->options.seeds, "Noise seeds of Figs. 8-11")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  paper->add_option("--modes", args->modes, "Simulator modes")
      ->capture_default_str()
      ->check(CLI::IsMember(enum_name_list<experiments::SimMode>()))
      ->delimiter(',');
  paper
      ->add_option("--wear-rl", args->options.setup.wear_rl_mm,
                   "True rear-left wear of the section 5 runs, mm of radius")
      ->capture_default_str()
      ->check(finite_in(kTyreWearMm));
  paper
      ->add_option("--wear-rr", args->options.setup.wear_rr_mm,
                   "True rear-right wear of the section 5 runs, mm of radius")
      ->capture_default_str()
      ->check(finite_in(kTyreWearMm));
  paper
      ->add_option("--laps", args->options.setup.laps,
                   "Laps of the section 5 runs (the paper: 3; fewer for a quick look)")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  paper->add_flag("--fresh", args->options.fresh,
                  "Recompute every piece instead of reusing finished ones");
  paper->callback([args] { run_paper(*args); });
}

}  // namespace odocal::cli
