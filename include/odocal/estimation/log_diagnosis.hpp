#pragma once
// `odocal doctor`: the input mistakes that make a calibration wrong, found by comparing the
// streams with each other before anything is estimated: wheels against GNSS speed (sign, unit,
// circumference), the yaw rates of wheels, gyro, GNSS course and heading stream (left/right,
// axes, conventions), the streams' clocks (scale, offset, span), repeated GNSS fixes, gaps and
// the zero-rate biases at standstill. Each finding says what, the evidence in numbers, the likely
// cause and the one-line fix. docs/doctor.md lists every check.

#include <limits>
#include <string>
#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/data/log_source.hpp"

namespace odocal {

enum class FindingSeverity {
  kBlocking,  // a calibration of this log would be wrong: calibrate refuses it (--force)
  kWarning,   // the calibration copes (or is less accurate): worth fixing
  kNote,      // how the log is, for the record
};

struct Finding {
  std::string check;  // stable identifier, e.g. "wheels.rl_sign"
  FindingSeverity severity{};
  std::string what;      // the finding
  std::string evidence;  // numbers
  std::string cause;     // the likely cause
  std::string fix;       // which map or vehicle.yaml key, and its value
  // The estimated quantity where the fix is a number (a clock offset in seconds: the stream's
  // time minus the wheels'); NaN otherwise.
  double estimate = std::numeric_limits<double>::quiet_NaN();
};

struct Diagnosis {
  std::vector<Finding> findings;
  double compared_s{};  // span of wheels and GNSS compared
  bool blocking() const;
};

Diagnosis diagnose_log(const Log& log);
// The same a block at a time (a log streamed from its files: the doctor holds its 10 Hz grid,
// never the log).
Diagnosis diagnose_log(LogBlockSource& source);

const char* severity_name(FindingSeverity severity);
// One line: "[blocking] what: evidence; likely cause; fix: ...".
std::string describe(const Finding& finding);

}  // namespace odocal
