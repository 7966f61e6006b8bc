#include "experiments/paper_experiment.hpp"

#include <fmt/chrono.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <functional>

#include "experiments/experiment_progress.hpp"
#include "experiments/gnss_robustness.hpp"
#include "experiments/json_file.hpp"
#include "experiments/monte_carlo.hpp"
#include "experiments/piece_cache.hpp"
#include "experiments/single_run.hpp"
#include "experiments/tyre_model_experiment.hpp"
#include "experiments/wear_table.hpp"
#include "odocal/error.hpp"
#include "odocal/io/calibration_io.hpp"
#include "odocal/io/scenario_io.hpp"

namespace odocal::experiments {
namespace {

// Bump when an experiment's code changes what it writes: finished pieces are then recomputed.
constexpr int kExperimentVersion = 8;

std::string stamp(const std::string& piece, const sim::Scenario& scenario) {
  return nlohmann::json{{"version", kExperimentVersion},
                        {"piece", piece},
                        {"scenario", scenario_to_yaml(scenario)},
                        {"calibration", config_to_json(CalibrationConfig{})}}
      .dump();
}

class PieceRunner {
 public:
  PieceRunner(bool fresh, ExperimentProgress& progress) : cache_(fresh), progress_(progress) {}

  void run(const std::string& label, const std::filesystem::path& dir, const std::string& key,
           const std::function<void()>& compute) {
    progress_.begin(label);
    const bool reuse = cache_.reusable(dir, key);
    if (!reuse) {
      cache_.open(dir);
      compute();
      cache_.mark_done(dir, key);
    }
    reused_ += reuse;
    progress_.end(reuse);
  }
  int reused() const { return reused_; }

 private:
  PieceCache cache_;
  ExperimentProgress& progress_;
  int reused_ = 0;
};

}  // namespace

std::string PaperExperimentOptions::validate() const {
  if (seeds < 1) return "seeds must be at least 1";
  if (modes.empty()) return "at least one simulator mode is needed";
  if (setup.wear_rl_mm < 0 || setup.wear_rr_mm < 0) return "tyre wear must not be negative";
  if (setup.laps < 1) return "laps must be at least 1";
  if (setup.track_csv && !std::filesystem::exists(*setup.track_csv))
    return "track file " + setup.track_csv->string() + " does not exist";
  return "";
}

void run_paper_experiment(const PaperExperimentOptions& options, std::FILE* progress_out) {
  if (const std::string problem = options.validate(); !problem.empty())
    throw Error("invalid experiment options: " + problem);
  const int per_mode = 2 + options.seeds;
  const auto has_mode = [&](SimMode mode) {
    return std::find(options.modes.begin(), options.modes.end(), mode) != options.modes.end();
  };
  const bool robustness = options.robustness && has_mode(SimMode::kIdeal);
  const bool tyre_models =
      options.tyre_models && has_mode(SimMode::kIdeal) && has_mode(SimMode::kRealistic);
  ExperimentProgress progress(progress_out, per_mode * static_cast<int>(options.modes.size()) +
                                                (robustness ? options.seeds : 0) +
                                                (tyre_models ? 2 * options.seeds : 0));
  PieceRunner runner(options.fresh, progress);
  const std::filesystem::path& out = options.out_dir;
  const std::uint64_t single_seed = 1;

  for (const SimMode mode : options.modes) {
    const std::string name = mode_name(mode);
    runner.run(fmt::format("Table 1 / Fig. 2, parking garage, {}", name), out / "table1" / name,
               stamp("table1", parking_scenario(mode)),
               [&] { run_wear_table(mode, out / "table1" / name); });
    runner.run(fmt::format("Figs. 4-7 and 12, one run, {}", name), out / "single" / name,
               stamp("single", paper_scenario(options.setup, mode, single_seed)),
               [&] { run_single(options.setup, mode, single_seed, out / "single" / name); });

    std::vector<nlohmann::json> seeds;
    for (int seed = 1; seed <= options.seeds; ++seed) {
      const std::filesystem::path dir =
          out / "monte_carlo" / name / fmt::format("seed-{:02}", seed);
      const auto noise_seed = static_cast<std::uint64_t>(seed);
      runner.run(fmt::format("Figs. 8-11, Monte Carlo, {}: seed {}/{}", name, seed, options.seeds),
                 dir, stamp("monte_carlo", paper_scenario(options.setup, mode, noise_seed)), [&] {
                   write_json_file(dir / "result.json",
                                   run_monte_carlo_seed(options.setup, mode, noise_seed));
                 });
      seeds.push_back(read_json_file(dir / "result.json"));
    }
    const nlohmann::json summary = summarise_monte_carlo(seeds);
    write_json_file(out / "monte_carlo" / name / "summary.json", summary);
    write_monte_carlo_summary_csv(summary, out / "monte_carlo" / name / "summary.csv");
  }

  if (robustness) {
    const DegradedGnss gnss;
    std::vector<nlohmann::json> seeds;
    for (int seed = 1; seed <= options.seeds; ++seed) {
      const std::filesystem::path dir = out / "robustness" / fmt::format("seed-{:02}", seed);
      const auto noise_seed = static_cast<std::uint64_t>(seed);
      runner.run(
          fmt::format("degraded GNSS, batch vs iterative: seed {}/{}", seed, options.seeds), dir,
          stamp("robustness", paper_scenario(options.setup, SimMode::kIdeal, noise_seed)), [&] {
            write_json_file(dir / "result.json",
                            run_robustness_seed(options.setup, gnss, noise_seed));
          });
      seeds.push_back(read_json_file(dir / "result.json"));
    }
    write_json_file(out / "robustness" / "summary.json", summarise_robustness(seeds));
  }

  if (tyre_models) {
    std::vector<nlohmann::json> seeds, urban;
    for (int seed = 1; seed <= options.seeds; ++seed) {
      const std::filesystem::path dir = out / "tyre_models" / fmt::format("seed-{:02}", seed);
      const auto noise_seed = static_cast<std::uint64_t>(seed);
      runner.run(
          fmt::format("tyre models, rear and front drive: seed {}/{}", seed, options.seeds), dir,
          stamp(fmt::format("tyre_models v{}", kTyreModelExperimentVersion),
                paper_scenario(options.setup, SimMode::kRealistic, noise_seed)),
          [&] {
            write_json_file(dir / "result.json", run_tyre_model_seed(options.setup, noise_seed));
          });
      seeds.push_back(read_json_file(dir / "result.json"));
      const std::filesystem::path urban_dir =
          out / "tyre_models" / fmt::format("urban-{:02}", seed);
      runner.run(
          fmt::format("tyre models, urban drift: seed {}/{}", seed, options.seeds), urban_dir,
          stamp(fmt::format("tyre_models_urban v{}", kTyreModelExperimentVersion),
                load_scenario("urban")),
          [&] { write_json_file(urban_dir / "result.json", run_urban_drift_seed(noise_seed)); });
      urban.push_back(read_json_file(urban_dir / "result.json"));
    }
    write_json_file(out / "tyre_models" / "summary.json", summarise_tyre_models(seeds, urban));
  }

  nlohmann::json modes = nlohmann::json::array();
  for (const SimMode mode : options.modes) modes.push_back(mode_name(mode));
  write_json_file(
      out / "experiment.json",
      {{"date",
        fmt::format("{:%Y-%m-%d %H:%M} UTC", fmt::gmtime(std::chrono::system_clock::to_time_t(
                                                 std::chrono::system_clock::now())))},
       {"command", options.command_line},
       {"track", options.setup.track_csv ? options.setup.track_csv->string() : "built-in circuit"},
       {"wear_rl_mm", options.setup.wear_rl_mm},
       {"wear_rr_mm", options.setup.wear_rr_mm},
       {"laps", options.setup.laps},
       {"seeds", options.seeds},
       {"modes", modes},
       {"elapsed_s", progress.elapsed_s()},
       {"pieces_reused", runner.reused()}});
  fmt::print(progress_out, "results in {} ({:.0f} s, {} pieces reused)\n", out.string(),
             progress.elapsed_s(), runner.reused());
}

}  // namespace odocal::experiments
