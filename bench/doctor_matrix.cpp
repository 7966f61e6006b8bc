// issue 16's acceptance matrix for `odocal doctor`: every fault kind (tests/support/
// doctor_faults.cpp) injected into realistic simulated drives of the circuit, urban and parking
// scenarios over several seeds (driver and sensor noise both), each counted as found when the
// doctor blocks and its blocking checks include the fault's; the same drives without a fault
// counted by their worst finding. Prints one table per scenario and the misses.
//
//   build/bench/odocal_doctor_matrix [--seeds 20] [--scenarios circuit,urban,parking]

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "../tests/support/doctor_faults.hpp"
#include "../tests/support/run_cli.hpp"
#include "odocal/io/log_doctor.hpp"

using namespace odocal;
namespace fs = std::filesystem;

namespace {

std::set<std::string> blocking_checks(const Diagnosis& diagnosis) {
  std::set<std::string> out;
  for (const Finding& f : diagnosis.findings)
    if (f.severity == FindingSeverity::kBlocking) out.insert(f.check);
  return out;
}

struct Tally {
  int found = 0, injected = 0, found_alone = 0;
  int clean = 0, clean_blocking = 0, clean_warning = 0, clean_note_only = 0;
  std::vector<std::string> misses;
  std::map<std::string, int> clean_checks;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"odocal doctor's fault-injection matrix over scenarios and seeds"};
  int seeds = 20;
  std::vector<std::string> scenarios = {"circuit", "urban", "parking"};
  app.add_option("--seeds", seeds, "Seeds per scenario")->check(CLI::Range(1, 1000));
  app.add_option("--scenarios", scenarios, "Built-in scenarios")->delimiter(',');
  CLI11_PARSE(app, argc, argv);

  const fs::path work = fs::temp_directory_path() / "odocal_doctor_matrix";
  const std::vector<testing::Fault> faults = testing::faults();
  for (const std::string& scenario : scenarios) {
    Tally tally;
    for (int seed = 1; seed <= seeds; ++seed) {
      std::map<std::string, fs::path> clean_logs;  // by simulate flags
      for (const testing::Fault& fault : faults) clean_logs.emplace(fault.simulate, fs::path());
      int variant = 0;
      for (auto& [flags, log] : clean_logs) {
        log = work / fmt::format("{}-{}-{}", scenario, seed, variant++);
        fs::remove_all(log);
        const auto run = testing::run_cli(fmt::format(
            "simulate --scenario {} --laps 1 --seed {} --trajectory-seed {} {} {} --out {}",
            scenario, seed, seed, testing::kCleanLogFlags, flags, log.string()));
        if (run.status != 0) {
          fmt::print(stderr, "simulate failed: {}\n", run.err);
          return 1;
        }
        log = fs::canonical(log);
        const Diagnosis diagnosis = doctor_log(log);
        ++tally.clean;
        bool blocking = false, warning = false;
        for (const Finding& f : diagnosis.findings) {
          blocking = blocking || f.severity == FindingSeverity::kBlocking;
          warning = warning || f.severity == FindingSeverity::kWarning;
          ++tally.clean_checks[f.check];
        }
        tally.clean_blocking += blocking;
        tally.clean_warning += !blocking && warning;
        tally.clean_note_only += !blocking && !warning && !diagnosis.findings.empty();
      }
      for (const testing::Fault& fault : faults) {
        const fs::path log = work / "faulty";
        fs::remove_all(log);
        fs::copy(clean_logs.at(fault.simulate), log);
        fault.inject(log);
        ++tally.injected;
        const Diagnosis diagnosis = testing::doctor_directory(log);
        const std::set<std::string> checks = blocking_checks(diagnosis);
        if (testing::found(diagnosis, fault)) {
          ++tally.found;
          // Named alone: every other blocking check is of the same stream (a unit on both
          // wheels is wheels.rl_unit and wheels.rr_unit).
          const std::string family = std::string(fault.expected_check)
                                         .substr(0, std::string(fault.expected_check).find('.'));
          std::string others;
          for (const std::string& c : checks)
            if (!c.starts_with(family)) others += " " + c;
          if (others.empty()) {
            ++tally.found_alone;
          } else {
            tally.misses.push_back(
                fmt::format("seed {}: {} -> found, also{}", seed, fault.name, others));
          }
        } else {
          std::string got;
          for (const std::string& c : checks) got += (got.empty() ? "" : " ") + c;
          for (const Finding& f : diagnosis.findings)
            if (f.severity != FindingSeverity::kBlocking) got += (got.empty() ? "" : " ") + f.check;
          tally.misses.push_back(
              fmt::format("seed {}: {} -> {}", seed, fault.name, got.empty() ? "nothing" : got));
        }
      }
      for (auto& [flags, log] : clean_logs) fs::remove_all(log);
    }
    fmt::print(
        "{}: faults found {}/{} ({:.1f} %), {} of them with no other stream blamed; clean logs "
        "{}: {} blocking, {} with a warning at most, {} with notes only\n",
        scenario, tally.found, tally.injected, 100.0 * tally.found / tally.injected,
        tally.found_alone, tally.clean, tally.clean_blocking, tally.clean_warning,
        tally.clean_note_only);
    for (const auto& [check, count] : tally.clean_checks)
      fmt::print("  clean-log finding {} x{}\n", check, count);
    for (const std::string& miss : tally.misses) fmt::print("  missed {}\n", miss);
  }
  fs::remove_all(work);
  return 0;
}
