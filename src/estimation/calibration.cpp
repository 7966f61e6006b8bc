#include "odocal/estimation/calibration.hpp"

#include <array>

namespace odocal {

OptionTable<CalibrationConfig> CalibrationConfig::fields() {
  static const std::array<OptionField<CalibrationConfig>, 1> kFields{{
      {"method", "", 0, 0, "the estimator (docs/calibration.md, docs/batch-calibration.md)",
       enum_member<&CalibrationConfig::method>()},
  }};
  return kFields;
}

std::string CalibrationConfig::validate() const {
  const auto in = [](const char* section, std::string problem) {
    return problem.empty() ? problem : std::string(section) + problem;
  };
  for (std::string problem :
       {common.validate(), in("", iterative.validate()), in("augmented.", augmented.validate()),
        in("batch.", batch.validate())}) {
    if (!problem.empty()) return problem;
  }
  return "";
}

AnyCalibrationSummary calibrate(const Log& log, const CalibrationConfig& config) {
  switch (config.method) {
    case CalibrationMethod::kFixedP:
      return calibrate_fixed_p(log, config.iterative, config.common);
    case CalibrationMethod::kAugmented:
      return calibrate_augmented(log, config.augmented, config.common);
    case CalibrationMethod::kBatch:
      return calibrate_batch(log, config.batch, config.common);
    case CalibrationMethod::kIterative:
      break;
  }
  return calibrate_iterative(log, config.iterative, config.common);
}

const CalibrationSummary& core(const AnyCalibrationSummary& summary) {
  return std::visit([](const auto& s) -> const CalibrationSummary& { return s; }, summary);
}

std::string full_report(const AnyCalibrationSummary& summary) {
  return std::visit([](const auto& s) { return s.full_report(); }, summary);
}

}  // namespace odocal
