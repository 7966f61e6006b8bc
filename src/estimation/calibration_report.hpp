#pragma once
// The parts of the text reports that every method's full_report() shares: the heading and the
// estimates, and at the end the whole-log dead reckoning and the outcome.

#include <string>

#include "odocal/estimation/calibration_summary.hpp"

namespace odocal {

// "method ...", then c_RL and c_RR with their change from nominal and 1-sigma.
std::string report_heading(const CalibrationSummary& summary);
// The dead reckoning before and after, and whether the result is usable and why.
std::string report_ending(const CalibrationSummary& summary);

}  // namespace odocal
