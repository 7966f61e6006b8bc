// The calibration config: one field table per options struct drives validate(), the YAML
// reader, the JSON writer and --print-config, so all four agree on every key.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "odocal/error.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/io/calibration_io.hpp"

namespace odocal {
namespace {

// Calls check(section, key, field, object) for every field of every section.
template <typename Check>
void for_each_field(CalibrationConfig& config, Check&& check) {
  for_each_config_section(config, [&](const char* section, const char*, auto table, auto& options) {
    for (const auto& field : table) check(std::string(section), field, options);
  });
}

TEST(CalibrationConfig, DefaultsAreValidAndKeysAreUniquePerSection) {
  CalibrationConfig config;
  EXPECT_EQ(config.validate(), "");
  std::set<std::string> keys;
  for_each_field(config, [&](const std::string& section, const auto& field, auto&) {
    EXPECT_TRUE(keys.insert(section + "." + field.key).second) << section << "." << field.key;
    EXPECT_NE(std::string(field.doc), "") << field.key;
  });
  EXPECT_GT(keys.size(), 60u);
}

TEST(CalibrationConfig, ValidateRejectsEveryNumericFieldOutsideItsRangeOrNaN) {
  int checked = 0;
  CalibrationConfig probe;
  for_each_field(probe, [&](const std::string& section, const auto& field, auto& options) {
    using Options = std::decay_t<decltype(options)>;
    const bool numeric = !std::holds_alternative<bool Options::*>(field.member) &&
                         !std::holds_alternative<EnumMember<Options>>(field.member);
    if (!numeric) return;
    const double above = field.max + 1.0 + std::abs(field.max);
    const double below = field.min - 1.0 - std::abs(field.min);
    for (const double bad : {std::nan(""), above, below}) {
      CalibrationConfig config;
      Options* target = nullptr;  // the same sub-struct inside `config`
      for_each_config_section(config, [&](const char* s, const char*, auto, auto& o) {
        if constexpr (std::is_same_v<std::decay_t<decltype(o)>, Options>)
          if (section == s) target = &o;
      });
      ASSERT_NE(target, nullptr);
      if (const auto* d = std::get_if<double Options::*>(&field.member)) {
        target->** d = bad;
      } else if (const auto* v = std::get_if<Eigen::Vector3d Options::*>(&field.member)) {
        (target->**v)(1) = bad;
      } else if (const auto* i = std::get_if<int Options::*>(&field.member)) {
        if (std::isnan(bad) || std::abs(bad) > 2e9) continue;  // no int holds it
        target->** i = static_cast<int>(bad);
      } else if (const auto* n = std::get_if<std::size_t Options::*>(&field.member)) {
        if (std::isnan(bad) || bad < 0) continue;
        target->** n = static_cast<std::size_t>(bad);
      }
      const std::string problem = config.validate();
      EXPECT_NE(problem.find(field.key), std::string::npos) << field.key << " = " << bad;
    }
    ++checked;
  });
  EXPECT_GE(checked, 50);  // the numeric fields of the six tables
}

TEST(CalibrationConfig, PrintedYamlReadsBackToTheSameConfig) {
  CalibrationConfig config;
  config.method = CalibrationMethod::kBatch;
  config.common.reference.mode = ReferenceMode::kSmoother;
  config.common.reference.gnss_sigma_m = 0.1 + 0.2;  // not exactly representable in decimal
  config.common.dr_start = DeadReckoningStart::kAlignedWhole;
  config.iterative.ls_weights = Eigen::Vector3d(1.0 / 3.0, 2.0, 1e-7);
  config.augmented.initial_param_sigma_m = 0.0123456789012345;
  config.batch.gnss_loss = RobustLoss::kHuber;
  config.batch.estimate_latency = true;
  config.batch.max_solver_iterations = 77;
  const std::string yaml = config_to_yaml(config);
  const CalibrationConfig back = parse_calibration_config(yaml, "printed.yaml");
  EXPECT_EQ(config_to_json(back), config_to_json(config)) << yaml;
  EXPECT_EQ(back.common.reference.gnss_sigma_m, 0.1 + 0.2);
  EXPECT_EQ(back.iterative.ls_weights, config.iterative.ls_weights);
  // Every key of the JSON appears in the YAML: one schema for both.
  const nlohmann::json json = config_to_json(config);
  for (const auto& [key, value] : json.items()) {
    EXPECT_NE(yaml.find(key + ":"), std::string::npos) << key;
    if (!value.is_object()) continue;
    for (const auto& [inner, ignored] : value.items())
      EXPECT_NE(yaml.find("  " + inner + ":"), std::string::npos) << key << "." << inner;
  }
}

TEST(CalibrationConfig, BadValuesNameFileLineAndKey) {
  const auto error_of = [](const std::string& yaml) {
    try {
      parse_calibration_config(yaml, "c.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of("method: fast\n"),
            "c.yaml:1: 'method': expected iterative, fixed-p, augmented or batch");
  EXPECT_EQ(error_of("batch:\n  gnss_loss: l1\n"),
            "c.yaml:2: 'batch.gnss_loss': expected none, huber or cauchy");
  EXPECT_EQ(error_of("min_reference_samples: 10.5\n"),
            "c.yaml:1: 'min_reference_samples': expected an integer");
  EXPECT_EQ(error_of("ls_weights: [1, 2]\n"),
            "c.yaml:1: 'ls_weights': expected a list of 3 numbers, each from 1e-12 to 1e+12");
  EXPECT_EQ(error_of("batch:\n  keyframe_interval_s: 0\n"),
            "c.yaml:2: 'batch.keyframe_interval_s': 0 is out of range: expected a finite number "
            "from 0.001 to 10000");
  EXPECT_EQ(error_of("augmented:\n  typo: 1\n"), "c.yaml:2: 'augmented.typo': unknown key");
  EXPECT_EQ(error_of("method: batch\nmethod: iterative\n"), "c.yaml:2: 'method': key given twice");
  EXPECT_EQ(error_of("? [a, b]\n: 1\n"),
            "c.yaml:1: a key must be a plain name, not a list or a mapping");
  EXPECT_EQ(error_of("batch:\n  ? {x: 1}\n  : 2\n"),
            "c.yaml:2: 'batch': a key must be a plain name, not a list or a mapping");
  EXPECT_EQ(error_of("reference:\n  acc_bias_sigma_mps2: -1\n"),
            "c.yaml:2: 'reference.acc_bias_sigma_mps2': -1 is out of range: expected a finite "
            "number from 0 to 100");
}

}  // namespace
}  // namespace odocal
