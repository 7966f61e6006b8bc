// What the batch's detections share (latency_detection, mounting_detection): a second fit of the
// log with something estimated that the first held, kept or dropped by what it found.
#pragma once

#include <array>
#include <string_view>

#include "odocal/estimation/batch_calibration.hpp"

namespace odocal::batch {

// The second fit stands where it converged or only left a parameter unidentified.
bool second_fit_stood(const BatchSummary& with);

// The summary's circumferences at rest, c_RL and c_RR (m): what a detection records of a fit.
std::array<double, 2> circumferences(const BatchSummary& summary);

// The named parameter where the fit estimated it with a finite, positive sigma; null otherwise.
const EstimatedParameter* estimated_parameter(const BatchSummary& summary, std::string_view name);

// `with` where taken, `without` otherwise, carrying the other's solves (the report counts them).
BatchSummary keep_one_fit(BatchSummary without, BatchSummary with, bool take_with);

}  // namespace odocal::batch
