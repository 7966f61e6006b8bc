// The doctor's checks of the IMU and the Doppler speed: axes, units and biases at standstill.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "doctor.hpp"
#include "doppler_scale.hpp"
#include "normal_equations.hpp"
#include "odocal/estimation/median.hpp"
#include "odocal/estimation/standstill.hpp"
#include "odocal/model/angle.hpp"
#include "odocal/model/gravity.hpp"
#include "sample_mean.hpp"

namespace odocal::detail {
namespace {

// A sensor's mean reading over the standstills, and whether it stands beyond `floor` and its own
// noise over them (4 standard errors): a bias, not the noise of a few standing seconds.
struct StandingMean {
  double mean{}, standard_error{};
  std::size_t samples{};
  bool beyond(double floor) const {
    return samples > 10 && std::abs(mean) > std::max(floor, 4.0 * standard_error);
  }
};

StandingMean standing_mean(const WindowSum& sums) {
  StandingMean out;
  out.samples = sums.count;
  if (sums.count == 0) return out;
  const double n = static_cast<double>(sums.count);
  out.mean = sums.sum / n;
  const double spread =
      sums.count > 1 ? std::sqrt(std::max(0.0, (sums.sum_squares - sums.sum * out.mean) / (n - 1)))
                     : 0.0;
  out.standard_error = spread / std::sqrt(n);
  return out;
}

// The drive reads the accelerometer's forward offset more closely than the standstills where
// they have no reading, or one of a wider standard error (one stop of a second: the body rocks).
bool drive_reads_offset_better(const DiagnosisFacts& facts) {
  const auto& drive = facts.drive_forward_offset;
  if (!drive) return false;
  const StandingMean standing = standing_mean(facts.ax_standing);
  return standing.samples <= 10 || drive->sigma_mps2 < standing.standard_error;
}

}  // namespace

void Doctor::check_imu_axes() {
  if (signals_.gyro_radps.empty() || count(turning_) < 50) return;
  // The wheels' yaw rate unless they are the ones found swapped.
  const auto& yaw_rate =
      has("wheels.swapped") ? signals_.gyro_radps : signals_.wheel_yaw_rate_radps;
  std::vector<double> centripetal(signals_.size());
  for (std::size_t k = 0; k < signals_.size(); ++k)
    centripetal[k] = signals_.gnss_speed_mps[k] * yaw_rate[k];
  const double with_ay = correlation(centripetal, signals_.ay_mps2, turning_);
  const double with_ax = correlation(centripetal, signals_.ax_mps2, turning_);
  const std::string evidence =
      fmt::format("correlation with speed x yaw rate: ay {:+.2f}, ax {:+.2f}", with_ay, with_ax);
  if (std::abs(with_ax) > 0.5 && std::abs(with_ax) > std::abs(with_ay) + 0.2) {
    add("imu.axes_swapped", FindingSeverity::kBlocking, "the IMU's x and y axes are swapped",
        evidence, "the IMU is mounted turned by 90 deg, or its columns are mixed up",
        "swap ax and ay");
  } else if (with_ay < -0.5) {
    add("imu.ay_sign", FindingSeverity::kBlocking, "the lateral acceleration has the wrong sign",
        evidence, "a forward-right-down IMU read as forward-left-up",
        "negate ay (import map: imu frame: frd)");
  }
}

void Doctor::check_imu_place() {
  if (signals_.gyro_radps.empty() || has("imu.axes_swapped") || has("imu.ay_sign") ||
      has("imu.yaw_sign") || has("imu.yaw_unit"))
    return;
  // Over each row's second the accelerometer's mean lateral reading less the wheels' speed times
  // the gyro's mean is x times the gyro's change over that second, less y times the gyro's
  // square (an IMU left of the axle reads its turns' centripetal -w^2 y). Below 8 m/s the rear
  // axle's side slip changes too little to matter (x read 1.20-1.53 m on the simulator's car at
  // 1.45 m, the lowest on the circuit's slow parts); a yaw misalignment of the IMU leaks its
  // forward reading in, so that is fitted beside (with the offset).
  constexpr double kMaxSpeedMps = 8.0, kMinSpeedMps = 1.0;
  const auto half = static_cast<std::size_t>(std::lround(0.5 / signals_.step_s));
  const double second_s = 2.0 * static_cast<double>(half) * signals_.step_s;
  NormalEquations<4> equations;
  for (std::size_t k = half; k + half < signals_.size(); ++k) {
    const double speed = 0.5 * (signals_.speed_rl_mps[k] + signals_.speed_rr_mps[k]);
    const double turn = signals_.gyro_radps[k];
    const double turn_change =
        (signals_.gyro_radps[k + half] - signals_.gyro_radps[k - half]) / second_s;
    const double excess = signals_.ay_mps2[k] - speed * turn;
    if (!(speed > kMinSpeedMps && speed < kMaxSpeedMps) || !std::isfinite(turn_change) ||
        !std::isfinite(excess) || !std::isfinite(signals_.ax_mps2[k]))
      continue;
    equations.add({turn_change, -turn * turn, signals_.ax_mps2[k], 1.0}, excess);
  }
  if (equations.rows() < 100) return;
  // The rows overlap over their second: each 2 half of them read one independent second.
  const auto fit = equations.solve(2.0 * static_cast<double>(half));
  if (!fit) return;
  const Eigen::Vector2d stated = facts_.vehicle.imu_position_m.value_or(Eigen::Vector2d::Zero());
  const Eigen::Vector2d read = fit->coefficients.head<2>(), sigma = fit->sigma.head<2>();
  constexpr double kMinGapM = 0.5;
  const auto stands_out = [&](int i) {
    const double gap = std::abs(read(i) - stated(i));
    return std::isfinite(sigma(i)) && sigma(i) <= 0.15 && gap >= kMinGapM && gap >= 5.0 * sigma(i);
  };
  if (!stands_out(0) && !stands_out(1)) return;
  const auto along = [](double value, const char* positive, const char* negative) {
    return std::abs(value) < 0.25
               ? std::string()
               : fmt::format("{:.1f} m {}", std::abs(value), value > 0.0 ? positive : negative);
  };
  std::string place = along(read.x(), "ahead of", "behind");
  const std::string side = along(read.y(), "left of", "right of");
  if (!place.empty() && !side.empty()) place += " and ";
  place += side;
  place = place.empty() ? "at the rear axle" : place + " the rear axle";
  const bool side_only = !stands_out(0);
  add("imu.place", FindingSeverity::kWarning,
      fmt::format("imu.csv's accelerometer reads the turns as an IMU {} would; vehicle.yaml has "
                  "imu_x_m {:.2f} m, imu_y_m {:.2f} m",
                  place, stated.x(), stated.y()),
      fmt::format("lateral acceleration less speed x yaw rate against the yaw rate's change and "
                  "its square, {} rows below {:.0f} m/s: x = {:+.2f} +- {:.2f} m, y = {:+.2f} "
                  "+- {:.2f} m",
                  equations.rows(), kMaxSpeedMps, read.x(), sigma.x(), read.y(), sigma.y()),
      !facts_.vehicle.imu_position_m
          ? "the IMU is mounted away from the rear axle (at the centre of gravity, under "
            "a seat) and vehicle.yaml does not say so: layer 1 takes the accelerations "
            "of its turns as the axle's"
      : side_only ? "vehicle.yaml's imu_y_m is not where the IMU is (left of the rear axle's "
                    "centre, in metres)"
                  : "vehicle.yaml's imu_x_m is not where the IMU is (forward of the rear "
                    "axle's centre, in metres)",
      fmt::format("vehicle.yaml: imu_x_m: {:.1f}, imu_y_m: {:.1f} (better: measure it on the car)",
                  read.x(), read.y()));
}

void Doctor::check_heading_offset() {
  const auto& offsets = signals_.heading_minus_course_rad;
  if (offsets.size() != signals_.size() || has("heading.convention") || has("gnss.mirrored"))
    return;
  // Medians of blocks of 5 s of straight driving each: the chord's course errs alike over its 4 s,
  // so the blocks' scatter gives the standard error, and a block's median shrugs off a manoeuvre.
  constexpr double kBlockS = 5.0;
  constexpr std::size_t kMinBlocks = 5;
  const auto rows_per_block =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(kBlockS / signals_.step_s)));
  std::vector<double> block_medians, block;
  std::size_t straight_rows = 0;
  for (const double offset : offsets) {
    if (!std::isfinite(offset)) continue;
    block.push_back(offset);
    ++straight_rows;
    if (block.size() == rows_per_block) {
      block_medians.push_back(median(block));
      block.clear();
    }
  }
  if (block_medians.size() < kMinBlocks) return;
  const auto [mean, standard_error] = sample_mean(block_medians);
  // Below a degree a mount's offset moves little (the batch looks for it from 0.003 rad).
  constexpr double kMinOffsetRad = 0.0175;
  if (std::abs(mean) < kMinOffsetRad || std::abs(mean) < 5.0 * standard_error) return;
  add("heading.offset", FindingSeverity::kWarning,
      fmt::format("heading.csv reads {:+.1f} deg beyond the GNSS course while driving straight",
                  deg_from_rad(mean)),
      fmt::format("{:+.2f} deg (standard error {:.2f} deg) over {:.0f} s straight above {:g} m/s",
                  deg_from_rad(mean), deg_from_rad(standard_error), seconds(straight_rows),
                  DiagnosisSignals::kCourseSpeedMps),
      "a heading sensor mounted at a yaw to the vehicle (a dual antenna's baseline, an IMU's "
      "orientation with its own zero)",
      "the batch finds and estimates it (detect_mounting, or estimate_heading_bias: true); for the "
      "other methods subtract it (import map: the heading's mounting yaw)");
}

bool Doctor::check_doppler_unit() {
  const auto& doppler = signals_.doppler_speed_mps;
  const auto& positions = signals_.position_speed_long_mps;
  if (doppler.size() != signals_.size() || positions.size() != signals_.size()) return false;
  std::vector<double> ratios;
  for (std::size_t k = 0; k < doppler.size(); ++k) {
    if (moving_[k] && !turning_[k] && positions[k] > 5.0 && std::isfinite(doppler[k]))
      ratios.push_back(doppler[k] / positions[k]);
  }
  const std::size_t compared = ratios.size();
  if (compared < 50) return false;
  const double ratio = median(std::move(ratios));
  if (std::abs(ratio - 1.0) <= 0.1) return false;
  std::string likely = likely_speed_unit(ratio);
  if (likely.empty()) likely = "the column is not a speed over ground in m/s";
  add("gnss.speed_unit", FindingSeverity::kBlocking, "the GNSS Doppler speed is not in m/s",
      fmt::format("median Doppler / position speed {:.3f} over {:.0f} s driving straight", ratio,
                  seconds(compared)),
      likely, "convert speed_mps to m/s (import map: speed unit), or drop the column");
  return true;
}

void Doctor::check_driving_forward_offset() {
  // Where no standstill reads it closely, the drive does: a phone pitched by 4 deg on a minute
  // of motorway (comma2k19). The same note as at standstill.
  constexpr double kMinAxOffsetMps2 = 0.1, kSignificantSigmas = 3.0;
  const auto& drive = facts_.drive_forward_offset;
  if (!drive_reads_offset_better(facts_) ||
      !(std::abs(drive->forward_mps2) >
        std::max(kMinAxOffsetMps2, kSignificantSigmas * drive->sigma_mps2)))
    return;
  const StandingMean standing = standing_mean(facts_.ax_standing);
  add("imu.ax_offset", FindingSeverity::kNote,
      fmt::format("the accelerometer reads {:+.2f} m/s^2 forward over the drive",
                  drive->forward_mps2),
      fmt::format(
          "{:+.3f} m/s^2 (1-sigma {:.3f}) over {:.0f} s of driving: the forward reading's "
          "integral less the speed the wheels gained, as a mount pitched by {:+.1f} deg "
          "reads; {}",
          drive->forward_mps2, drive->sigma_mps2, drive->duration_s,
          deg_from_rad(std::asin(std::clamp(drive->forward_mps2 / kGravityMps2, -1.0, 1.0))),
          standing.samples > 10 ? fmt::format("standing it reads {:+.3f} (standard error {:.3f})",
                                              standing.mean, standing.standard_error)
                                : std::string("no standstill to read it at")),
      "an IMU mounted pitched, or an accelerometer bias",
      "none needed for odocal: calibrate measures it over the drive where too few stops do and "
      "takes it out of ax (remove_accelerometer_offset); level the IMU for other uses of its "
      "forward reading");
}

void Doctor::check_standstill_biases() {
  if (!facts_.standing) {
    check_driving_forward_offset();
    return;
  }
  if (facts_.imu.samples > 0) {
    if (const StandingMean gyro = standing_mean(facts_.gyro_standing);
        gyro.beyond(rad_from_deg(0.2))) {
      add("imu.gyro_bias", FindingSeverity::kNote, "the gyro has a zero-rate bias",
          fmt::format("{:+.3f} deg/s at standstill ({} samples, standard error {:.3f} deg/s)",
                      deg_from_rad(gyro.mean), gyro.samples, deg_from_rad(gyro.standard_error)),
          "an uncalibrated gyro", "none needed: the reference filter estimates it");
    }
    // The physical tyre terms take the forward reading for the force the tyres push with: an
    // offset of 0.3 m/s^2 (a mount pitched by 1.75 deg) put the urban drive's circumferences
    // 4.5 mm off at a sigma of 0.62 mm until the preparation took it out at the stops, or the
    // sigma carried it (accelerometer_offset.hpp). Standing, the reading is the offset and the
    // slope where the car stood: a note, for whoever uses the log's ax elsewhere.
    constexpr double kMinAxOffsetMps2 = 0.1;
    if (const StandingMean ax = standing_mean(facts_.ax_standing);
        ax.beyond(kMinAxOffsetMps2) && !drive_reads_offset_better(facts_)) {
      add("imu.ax_offset", FindingSeverity::kNote,
          fmt::format("the accelerometer reads {:+.2f} m/s^2 forward at standstill", ax.mean),
          fmt::format("{:+.3f} m/s^2 over {} samples (standard error {:.3f}), as a mount pitched "
                      "by {:+.1f} deg reads",
                      ax.mean, ax.samples, ax.standard_error,
                      deg_from_rad(std::asin(std::clamp(ax.mean / kGravityMps2, -1.0, 1.0)))),
          "an IMU mounted pitched, an accelerometer bias, or the slope where the car stood",
          "none needed for odocal: it takes the offset out of ax where the stops measure it "
          "beyond their scatter, and carries it in the tyre model's sigma otherwise "
          "(remove_accelerometer_offset); level the IMU for other uses of its forward reading");
    }
  }
  check_driving_forward_offset();
  if (const auto& bias = facts_.wheel_rate_bias) {
    if (std::max(std::abs(bias->rl_rev_per_s), std::abs(bias->rr_rev_per_s)) * 360.0 > 0.1) {
      add("wheels.rate_bias", FindingSeverity::kNote,
          "the wheel rate sensors have zero-rate biases",
          fmt::format("RL {:+.3f} deg/s, RR {:+.3f} deg/s over {:.1f} s standing",
                      360.0 * bias->rl_rev_per_s, 360.0 * bias->rr_rev_per_s, bias->standing_s),
          "angular-rate wheel sensors read a little at rest",
          "none needed: removed before calibrating");
    }
  }
}

}  // namespace odocal::detail
