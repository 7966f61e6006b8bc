#pragma once
// The GNSS Doppler column's scale, judged before anything reads it (the layer-1 reference's speed
// update, the batch's Doppler fit): a column in km/h would otherwise pull the reference and the
// circumferences 3.6 times over, and the fit ends not usable for a cause ("too short") that is not
// the one.

#include <optional>
#include <string>

#include "odocal/data/log.hpp"

namespace odocal {

// "the speed is in km/h (x3.6)" where `ratio` (column over true speed) is within 5 % of a unit's
// factor to m/s (km/h, mph, knots, cm/s, mm/s); empty otherwise.
std::string likely_speed_unit(double ratio);

// The Doppler distance over another's, summed over the driving both cover (noise and latency
// average out), and the time compared.
struct DopplerScale {
  double ratio{};
  double compared_s{};
};

// The driving compared by default: the wheels above this speed, fixes at most this far apart.
inline constexpr double kDopplerJudgedSpeedMps = 5.0;
inline constexpr double kDopplerMaxFixGapS = 1.0;

// Against the wheels at `nominal`: between consecutive fixes at most max_gap_s apart while the
// wheels roll at least min_speed_mps (the wheels' speed, not the column's, whose scale is judged).
// None without a Doppler column or with less than 30 s of such driving.
std::optional<DopplerScale> doppler_over_wheels(const Log& log, const OdometryParams& nominal,
                                                double min_speed_mps = kDopplerJudgedSpeedMps,
                                                double max_gap_s = kDopplerMaxFixGapS);

// Against the positions: the chord of each 5 s stretch at the same speeds. The fixes' noise
// averages out over the stretches but lengthens each chord by about sigma^2 / length (1 % with
// 3 m on 25 m), and a turn shortens it by a few per cent at most: well inside the 10 % judged.
std::optional<DopplerScale> doppler_over_positions(const Log& log, const OdometryParams& nominal,
                                                   double min_speed_mps = kDopplerJudgedSpeedMps,
                                                   double max_gap_s = kDopplerMaxFixGapS);

// Throws InputError naming gnss.csv's speed_mps where the column is further than 10 % from both the
// wheels and the positions (from the wheels alone where the positions cover too little): wear and
// load move the wheels' scale by well under a per cent, a unit by far more. A column that agrees
// with the positions but not the wheels is the wheels' problem, left to the wheels' checks.
void check_doppler_scale(const Log& log, const OdometryParams& nominal);

}  // namespace odocal
