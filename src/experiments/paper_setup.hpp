#pragma once
// What the paper's experiments share: the simulator modes, the section 5 scenario (3 laps of
// Hockenheim, or the built-in circuit without the track file) and the paper's own figures that
// our results are printed beside.

#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "odocal/estimation/calibration.hpp"
#include "odocal/sim/scenario.hpp"

namespace odocal {
namespace experiments {

// kIdeal: the paper's model assumptions (exact path, no slip, constant radius); kRealistic: the
// dynamic vehicle with slip, load-dependent radius and side slip.
enum class SimMode { kIdeal, kRealistic };

}  // namespace experiments

template <>
struct EnumNames<experiments::SimMode> {
  static constexpr std::array<EnumName<experiments::SimMode>, 2> kTable{
      {{experiments::SimMode::kIdeal, "ideal"}, {experiments::SimMode::kRealistic, "realistic"}}};
};

}  // namespace odocal

namespace odocal::experiments {

inline const char* mode_name(SimMode mode) { return enum_name(mode); }

struct PaperSetup {
  std::optional<std::filesystem::path> track_csv;  // TUMFTM centreline; empty: built-in circuit
  double wear_rl_mm = 1.5;  // true rear tyre wear of the section 5 runs (the paper gives none)
  double wear_rr_mm = 1.0;
  int laps = 3;  // the paper's 3 laps
};

// The section 1 parking garage (Table 1, Fig. 2) in the given mode, wear as built in.
sim::Scenario parking_scenario(SimMode mode);

// The section 5 scenario with the paper's sensor noise, for one noise seed.
sim::Scenario paper_scenario(const PaperSetup& setup, SimMode mode, std::uint64_t noise_seed);

// The options each method runs with. Defaults throughout, except that the batch estimator's
// wheel noise matches the simulator mode: in ideal mode the truth has no slip and no side slip,
// so its odometry noise is set near zero (1e-6 m per sqrt(m)); realistic mode keeps the defaults.
CalibrationConfig method_options(CalibrationMethod method, SimMode mode);

// Table 1: rear tyre wear [mm of radius] and the paper's dead-reckoning errors.
struct PaperWearRow {
  double wear_rl_mm, wear_rr_mm;
  double mean_position_m, max_position_m, mean_heading_deg, max_heading_deg;
};
inline constexpr std::array<PaperWearRow, 7> kPaperTable1{{
    {0.0, 0.0, 0.34, 0.77, 0.53, 4.08},
    {1.5, 1.5, 1.26, 3.66, 1.54, 4.95},
    {3.0, 3.0, 2.61, 7.50, 2.89, 7.44},
    {6.0, 6.0, 5.37, 15.24, 5.79, 12.55},
    {3.1, 2.9, 6.33, 19.01, 8.33, 16.39},
    {3.25, 2.75, 12.90, 36.39, 16.47, 33.44},
    {3.5, 2.5, 24.19, 70.04, 30.16, 62.34},
}};

// Section 5 figures quoted beside ours.
inline constexpr double kPaperSingleRunErrorRlMm = 0.41;  // Fig. 7
inline constexpr double kPaperSingleRunErrorRrMm = 0.43;
inline constexpr double kPaperSingleRunMeanPositionM = 7.87;
inline constexpr double kPaperSingleRunMaxPositionM = 15.0;
inline constexpr double kPaperSingleRunMeanHeadingDeg = 0.93;
inline constexpr double kPaperSingleRunMaxHeadingDeg = 4.58;
inline constexpr double kPaperIterativeMeanAbsErrorMm = 0.86;  // Fig. 8, 10 seeds
inline constexpr double kPaperFixedPMeanAbsErrorMm = 1.39;
// Fig. 11: the iterative method "reduced around 50%" the augmented KF's mean absolute error.
inline constexpr double kPaperAugmentedMeanAbsErrorMm = 2.0 * kPaperIterativeMeanAbsErrorMm;

}  // namespace odocal::experiments
