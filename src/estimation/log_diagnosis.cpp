#include "odocal/estimation/log_diagnosis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "diagnosis_facts.hpp"
#include "diagnosis_signals.hpp"
#include "doctor.hpp"
#include "odocal/estimation/prepared_blocks.hpp"

namespace odocal {

bool Diagnosis::blocking() const {
  return std::any_of(findings.begin(), findings.end(),
                     [](const Finding& f) { return f.severity == FindingSeverity::kBlocking; });
}

const char* severity_name(FindingSeverity severity) {
  switch (severity) {
    case FindingSeverity::kBlocking:
      return "blocking";
    case FindingSeverity::kWarning:
      return "warning";
    case FindingSeverity::kNote:
      return "note";
  }
  return "?";
}

std::string describe(const Finding& finding) {
  std::string line =
      fmt::format("[{}] {}: {}", severity_name(finding.severity), finding.what, finding.evidence);
  if (!finding.cause.empty()) line += "; likely " + finding.cause;
  if (!finding.fix.empty()) line += "; fix: " + finding.fix;
  return line + " (" + finding.check + ")";
}

Diagnosis diagnose_log(LogBlockSource& source) {
  detail::DiagnosisSignals signals;
  detail::DiagnosisFacts facts = detail::diagnosis_facts(source, signals);
  return detail::Doctor(std::move(facts), std::move(signals)).run();
}

Diagnosis diagnose_log(const Log& log) {
  InMemoryLogSource source(log);
  return diagnose_log(source);
}

}  // namespace odocal
