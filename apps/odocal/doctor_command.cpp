#include "doctor_command.hpp"

#include <fmt/format.h>

#include <memory>
#include <nlohmann/json.hpp>

#include "exit_codes.hpp"
#include "odocal/error.hpp"
#include "odocal/estimation/log_diagnosis.hpp"
#include "odocal/io/log_doctor.hpp"
#include "odocal/io/output_file.hpp"

namespace odocal::cli {
namespace {

struct DoctorArgs {
  std::string log_dir;
  std::string json_file;
};

nlohmann::json to_json(const Diagnosis& diagnosis) {
  nlohmann::json findings = nlohmann::json::array();
  for (const Finding& f : diagnosis.findings) {
    findings.push_back({{"check", f.check},
                        {"severity", severity_name(f.severity)},
                        {"what", f.what},
                        {"evidence", f.evidence},
                        {"cause", f.cause},
                        {"fix", f.fix}});
  }
  return {{"blocking", diagnosis.blocking()},
          {"compared_s", diagnosis.compared_s},
          {"findings", findings}};
}

void run_doctor(const DoctorArgs& args) {
  Diagnosis diagnosis;
  try {
    diagnosis = doctor_log(args.log_dir);
  } catch (const InputError&) {
    // The log does not read: list the garbage in every column first, then the reader's error.
    for (const Finding& finding : scan_stream_values(args.log_dir))
      fmt::print("{}\n", describe(finding));
    throw;
  }
  fmt::print("doctor       {}: {:.0f} s of wheels and GNSS compared, {} finding(s)\n", args.log_dir,
             diagnosis.compared_s, diagnosis.findings.size());
  for (const Finding& finding : diagnosis.findings) fmt::print("{}\n", describe(finding));
  if (!args.json_file.empty()) write_output_file(args.json_file, to_json(diagnosis).dump(2) + "\n");
  if (diagnosis.blocking()) {
    throw NotUsableResult("findings that would make a calibration of this log wrong (above)");
  }
}

}  // namespace

void add_doctor_command(CLI::App& app) {
  auto args = std::make_shared<DoctorArgs>();
  CLI::App* command = app.add_subcommand(
      "doctor",
      "Find wiring, unit and clock mistakes in a log before they become a wrong calibration");
  command->add_option("LOG", args->log_dir, "Log directory")->required();
  command->add_option("--json", args->json_file, "Write the findings as JSON");
  command->callback([args] { run_doctor(*args); });
}

}  // namespace odocal::cli
