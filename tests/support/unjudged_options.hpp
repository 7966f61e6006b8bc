#pragma once
// Options for tests that check estimates, not the model-adequacy verdict: its batch fit would
// double their time under the sanitizers (model_adequacy_batch_test.cpp checks the verdict).

#include "odocal/estimation/calibration_options.hpp"

namespace odocal::testing {

inline CalibrationOptions unjudged_options() {
  CalibrationOptions options;
  options.judge_model_adequacy = false;
  return options;
}

}  // namespace odocal::testing
