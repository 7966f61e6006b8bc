#include "experiments/wear_table.hpp"

#include <vector>

#include "odocal/estimation/dead_reckoning.hpp"
#include "odocal/estimation/trajectory_errors.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/io/text_output.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal::experiments {
namespace {

constexpr std::size_t kPathStride = 5;

struct WearCase {
  TrajectoryErrors errors;
  PoseStream path;
};

}  // namespace

void run_wear_table(SimMode mode, const std::filesystem::path& dir) {
  std::vector<WearCase> cases;
  PoseStream truth;
  for (const PaperWearRow& paper : kPaperTable1) {
    sim::Scenario scenario = parking_scenario(mode);
    scenario.vehicle.wear_rl_mm = paper.wear_rl_mm;
    scenario.vehicle.wear_rr_mm = paper.wear_rr_mm;
    const Log log = simulated_log(sim::simulate(scenario), true);
    PoseStream path =
        dead_reckon(log.wheels, log.vehicle.nominal_params(), log.truth->pose.front());
    const TrajectoryErrors errors =
        trajectory_errors(path, reference_from_poses(*log.truth, "truth"));
    cases.push_back({errors, std::move(path)});
    if (truth.size() == 0) truth = *log.truth;
  }

  write_text_file(dir / "table1.csv", [&](TextBuffer& out) {
    out.print(
        "wear_rl_mm,wear_rr_mm,mean_position_m,max_position_m,mean_heading_deg,max_heading_deg,"
        "paper_mean_position_m,paper_max_position_m,paper_mean_heading_deg,"
        "paper_max_heading_deg\n");
    for (std::size_t row = 0; row < cases.size(); ++row) {
      const PaperWearRow& paper = kPaperTable1[row];
      const TrajectoryErrors& e = cases[row].errors;
      out.print("{},{},{:.4f},{:.4f},{:.4f},{:.4f},{},{},{},{}\n", paper.wear_rl_mm,
                paper.wear_rr_mm, e.mean_position_m, e.max_position_m,
                deg_from_rad(e.mean_heading_rad), deg_from_rad(e.max_heading_rad),
                paper.mean_position_m, paper.max_position_m, paper.mean_heading_deg,
                paper.max_heading_deg);
    }
  });
  write_text_file(dir / "paths.csv", [&](TextBuffer& out) {
    out.print("case,x_m,y_m\n");
    const auto write_path = [&](int label, const PoseStream& path) {
      for (std::size_t k = 0; k < path.size(); k += kPathStride)
        out.print("{},{:.3f},{:.3f}\n", label, path.pose[k].x(), path.pose[k].y());
    };
    write_path(-1, truth);
    for (std::size_t row = 0; row < cases.size(); ++row)
      write_path(static_cast<int>(row), cases[row].path);
  });
}

}  // namespace odocal::experiments
