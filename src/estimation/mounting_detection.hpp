// BatchOptions::detect_mounting: a GNSS antenna off the lever arm the fit holds, or a heading.csv
// read off the vehicle's heading by a mount's yaw, that the fit did not estimate. An antenna off
// the centreline runs y times the net turn shorter or longer than the wheels (the 2-hour urban
// drive of left-hand loops, without a Doppler column, 0.3 m left: the circumferences 4 mm low; on
// the 5-minute drive with one, 0.5 m: the Doppler speed's noise 6.5 times the configured and the
// fit refused), and a heading read 0.05 rad off pulls the poses' heading from the course (the
// same drive refused as dead-reckoning worse than nominal). Where the fit's residuals show it
// (MountingResiduals), calibrate_batch fits the log again with it estimated and takes that fit
// where what it finds is significant.
#pragma once

#include <array>
#include <optional>
#include <string>

#include "odocal/estimation/batch_calibration.hpp"

namespace odocal::batch {

// Below these a mounting moves the circumferences by about a tenth of a millimetre on the
// built-in urban drive's loops: not worth a second fit, nor taken from one.
inline constexpr double kMinLeverArmM = 0.05;
inline constexpr double kMinHeadingBiasRad = 0.003;

// Which of the two the fit's residuals show, beyond BatchOptions::kMountingSigmas of their
// standard error and the sizes above; none where neither (or each is estimated already).
struct MountingSignature {
  bool lever_arm{}, heading_bias{};
};
std::optional<MountingSignature> mounting_signature(const MountingResiduals& residuals,
                                                    const BatchOptions& options);

// What `with` found of what `shown` asks for: the values where estimated, whether each was
// (complete), and whether one lies beyond kMountingSigmas of its sigma and the sizes that matter
// from where `stated` holds it.
struct MountingFound {
  std::array<double, 2> lever_arm_m{}, lever_arm_sigma_m{};
  double heading_bias_rad{}, heading_bias_sigma_rad{};
  bool complete = true, significant = false;
};
MountingFound mounting_found(const BatchSummary& with, const MountingSignature& shown,
                             const BatchOptions& stated);

// `with`: the log calibrated with what the signature shows estimated. It stands where one of them
// lies beyond kMountingSigmas of its sigma (and the sizes above) from where `without` held it;
// either carries what was found (BatchSummary::mounting_detection) and the other's solves.
BatchSummary take_mounting_where_significant(BatchSummary without, BatchSummary with,
                                             const MountingSignature& signature,
                                             const BatchOptions& options);

// A latency found after a mounting that was taken: whether, with the latency estimated beside it,
// the mounting no longer lies beyond kMountingSigmas of its sigma and the sizes above from what
// `options` state (a lag along the track shows in the fixes' mean as an antenna behind the axle:
// the urban drive with the fixes 141 ms late, no antenna off the centre, gave one 0.68 m behind at
// 14 sigma, 0.02 m with the latency estimated too).
bool mounting_explained_by_latency(const BatchSummary& lagged, const BatchOptions& options);

// `lag_alone`: the log calibrated with the latency estimated and the mounting held as stated. It
// stands where it converged (or only left a parameter unidentified) and its latency is
// significant; then its summary carries the mounting as explained by the latency, not taken, and
// the latency as found against the fit with neither. Otherwise `lagged` stands as it is.
BatchSummary drop_mounting_explained_by_latency(BatchSummary lagged, BatchSummary lag_alone,
                                                const BatchOptions& options);

// The report's line on it.
std::string mounting_detection_report(const BatchSummary::MountingDetection& detection);

}  // namespace odocal::batch
