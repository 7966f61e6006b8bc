#include "drive_force_check.hpp"

#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "odocal/error.hpp"
#include "odocal/estimation/paired_moments.hpp"
#include "odocal/model/gravity.hpp"
#include "odocal/model/tyre_model.hpp"

namespace odocal::detail {
namespace {

constexpr double kMostGravities = 3.0;
constexpr double kBinS = 1.0;
constexpr double kMovingMps = 2.0;
constexpr double kRollingMps = 0.5;  // the braking check's: which way the car rolls is clear
constexpr std::size_t kFewestBins = 20;
constexpr double kLeastSpreadMps2 = 0.3;
constexpr double kLeastGain = 0.5, kMostGain = 2.0;
constexpr double kLeastCorrelation = 0.5;
// Seconds where the wheels slow by more than kBrakingMps2 beyond the road's resistance: the force
// must give at least kLeastBrakingShare of that braking.
constexpr double kBrakingMps2 = 0.5, kLeastBrakingShare = 0.25;
constexpr std::size_t kFewestBrakingBins = 5;

// Sums along the motion over the seconds of one kind (braking, or driving on): what the force
// per kilogram should be and what it is.
struct AlongMotion {
  double expected = 0.0, given = 0.0;
  std::size_t bins = 0;
  void add(double expected_mps2, double given_mps2) {
    expected += expected_mps2;
    given += given_mps2;
    ++bins;
  }
  double seconds() const { return static_cast<double>(bins) * kBinS; }
};

// One second of the log: the wheels' mean speed and the force's mean.
struct Bin {
  double centre_s = 0.0, seconds = 0.0, metres = 0.0, force_sum_n = 0.0;
  std::size_t rows = 0;
  double speed_mps() const { return metres / seconds; }
  double force_n() const { return force_sum_n / static_cast<double>(rows); }
};

std::vector<Bin> one_second_bins(const WheelStream& wheels, const std::vector<double>& force,
                                 const VehicleConfig& vehicle) {
  std::vector<Bin> bins;
  const double start = wheels.t_s.front();
  long current = -1;
  for (std::size_t k = 1; k < wheels.size(); ++k) {
    const long index = std::lround(std::floor((wheels.t_s[k] - start) / kBinS));
    if (index != current) {
      bins.push_back({start + (static_cast<double>(index) + 0.5) * kBinS});
      current = index;
    }
    Bin& bin = bins.back();
    bin.seconds += wheels.t_s[k] - wheels.t_s[k - 1];
    bin.metres += 0.5 * (wheels.rev_rl[k] * vehicle.circumference_rl_m +
                         wheels.rev_rr[k] * vehicle.circumference_rr_m);
    bin.force_sum_n += force[k];
    ++bin.rows;
  }
  return bins;
}

}  // namespace

void check_drive_force(const CsvTable& table, const WheelStream& wheels,
                       const VehicleConfig& vehicle) {
  const VehicleBody& body = vehicle.body;
  const double most_n = kMostGravities * kGravityMps2 * body.mass_kg;
  const std::vector<double>& force = table.column("drive_force_n");
  for (std::size_t k = 0; k < force.size(); ++k) {
    if (std::abs(force[k]) <= most_n) continue;
    throw InputError(table.at(k, "drive_force_n"),
                     fmt::format("{:.6g} N is more than {} g for the body's mass_kg {:g} (a torque "
                                 "in N m, or a force in another unit?)",
                                 force[k], kMostGravities, body.mass_kg));
  }
  // The force per kilogram against what the wheels say it should be: their acceleration (central
  // differences of 1 s mean speeds) and the drag and rolling resistance it overcomes.
  const std::vector<Bin> bins = one_second_bins(wheels, force, vehicle);
  PairedMoments moments;
  AlongMotion braking, driving;
  for (std::size_t i = 1; i + 1 < bins.size(); ++i) {
    const Bin &before = bins[i - 1], &here = bins[i], &after = bins[i + 1];
    if (after.centre_s - before.centre_s > 2.5 * kBinS || here.seconds < 0.5 * kBinS ||
        before.seconds <= 0.0 || after.seconds <= 0.0)
      continue;
    const double v = here.speed_mps();
    if (std::abs(v) < kRollingMps) continue;
    const double acceleration =
        (after.speed_mps() - before.speed_mps()) / (after.centre_s - before.centre_s);
    // Drag and rolling resistance oppose the motion, forward or reversing.
    const double resistance = std::copysign(road_resistance(body, std::abs(v)).total(), v);
    const double expected = acceleration + resistance, given = here.force_n() / body.mass_kg;
    // Braking or driving on, forward or reversing (a parking manoeuvre's too).
    const double forward = v > 0.0 ? 1.0 : -1.0;
    const double along = forward * expected;
    if (along < -kBrakingMps2) braking.add(along, forward * given);
    if (along > kBrakingMps2) driving.add(along, forward * given);
    if (std::abs(v) >= kMovingMps) moments.add(expected, given);
  }
  const InputLocation where{table.file, 1, "drive_force_n"};
  // Judged where the drive is long enough and its acceleration varies.
  const bool judged =
      moments.count() >= kFewestBins && moments.variance_x() >= kLeastSpreadMps2 * kLeastSpreadMps2;
  const double seconds = static_cast<double>(moments.count()) * kBinS;
  const double gain = moments.slope(), correlation = moments.correlation();
  // A force that does not vary at all correlates with nothing (NaN): refused as well.
  if (judged && !(std::abs(correlation) >= kLeastCorrelation)) {
    throw InputError(where, fmt::format("the force hardly follows the wheels' acceleration "
                                        "(correlation {:.2f} over {:.0f} s of driving): another "
                                        "clock, or another quantity?",
                                        correlation, seconds));
  }
  // A drive torque alone (the engine's, without the brakes') is right while the car drives on
  // and reads nothing while it brakes; over the whole drive its gain can pass.
  const double driving_gain = driving.given / driving.expected;
  if (braking.bins >= kFewestBrakingBins && driving.bins >= kFewestBrakingBins &&
      driving_gain >= kLeastGain && driving_gain <= kMostGain &&
      braking.given > kLeastBrakingShare * braking.expected) {
    throw InputError(
        where,
        fmt::format("the force hardly brakes: over {:.0f} s where the wheels slow the car by "
                    "{:.2f} m/s^2 beyond drag and rolling resistance it gives {:+.2f} m/s^2 over "
                    "the body's mass_kg {:g}, {:.2f} times what it should where the car drives on "
                    "(a drive torque without the brakes'? drive_force_n is the drive's force less "
                    "the brakes')",
                    braking.seconds(), -braking.expected / static_cast<double>(braking.bins),
                    braking.given / static_cast<double>(braking.bins), body.mass_kg, driving_gain));
  }
  if (judged && (gain < kLeastGain || gain > kMostGain)) {
    throw InputError(
        where, fmt::format(
                   "the force over the body's mass_kg {:g} is {:.3g} times the "
                   "wheels' acceleration with drag and rolling resistance over {:.0f} s of driving "
                   "(expected 1: a force in kN or daN, its sign turned, or the mass?)",
                   body.mass_kg, gain, seconds));
  }
}

}  // namespace odocal::detail
