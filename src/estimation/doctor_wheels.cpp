// The doctor's checks of the wheels against the GNSS and the gyro: units, signs, circumferences
// and the track width.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "diagnosis_track.hpp"
#include "doctor.hpp"
#include "odocal/estimation/median.hpp"

namespace odocal::detail {
namespace {

constexpr double kPi = std::numbers::pi;

// A ratio that a known unit mistake produces, within 4 %.
struct KnownFactor {
  double factor;
  const char* cause;
  const char* fix;
};

std::optional<KnownFactor> known_wheel_factor(double ratio, WheelUnit unit) {
  static const KnownFactor kFactors[] = {
      {180.0 / kPi, "wheel angles in degrees read as radians",
       "give the wheel columns in rad (or unit: deg in the import map)"},
      {kPi / 180.0, "wheel angles in radians read as degrees",
       "give the wheel columns in rad (or unit: rad in the import map)"},
      {60.0 / (2 * kPi), "wheel rates in rpm read as rad/s",
       "convert the wheel rates to rad/s (or unit: rpm in the import map)"},
      {2 * kPi / 60.0, "wheel rates in rad/s read as rpm",
       "give the wheel rates in rad/s (or unit: rad/s in the import map)"},
      {3.6, "wheel speeds in km/h read as m/s",
       "convert the wheel speeds to m/s (or unit: km/h in the import map)"},
      {1.0 / 3.6, "wheel speeds in m/s read as km/h",
       "give the wheel speeds in m/s (or unit: m/s in the import map)"},
      {1.0 / kPi, "a diameter where vehicle.yaml wants the circumference",
       "circumference = pi x diameter"},
      {1.0 / (2 * kPi), "a radius where vehicle.yaml wants the circumference",
       "circumference = 2 pi x radius"},
  };
  const auto near = [&](double factor) { return std::abs(ratio / factor - 1.0) < 0.04; };
  for (const KnownFactor& known : kFactors) {
    if (near(known.factor)) return known;
  }
  if (unit == WheelUnit::kTicks) {
    for (int n = 2; n <= 16; ++n) {
      if (near(n))
        return KnownFactor{double(n), "ticks_per_rev too small by an integer factor", ""};
      if (near(1.0 / n))
        return KnownFactor{1.0 / n, "ticks_per_rev too large by an integer factor", ""};
    }
  }
  return std::nullopt;
}

}  // namespace

bool Doctor::check_wheel_speeds() {
  if (count(moving_) < 50) {
    add("wheels.motion", FindingSeverity::kNote,
        "too little driving above 3 m/s to compare wheels with GNSS",
        fmt::format("{:.1f} s moving", seconds(count(moving_))), "", "");
    return false;
  }
  bool ok = true;
  // Driving straight where there is enough of it: in a tight turn the inner and outer wheels
  // run b/(2R) slower and faster than the GNSS antenna (10 % in a parking garage's 8 m turns).
  // Straight for the whole 6 s that the 4 s baseline's GNSS means span: there the long
  // baseline's speeds, with a tenth of the noise bias, are compared.
  std::vector<bool> straight(signals_.size()), straight_long(signals_.size());
  // Turning by the gyro where there is one: a wheel unit mistake scales the wheels' yaw rate.
  for (std::size_t k = 0; k < straight.size(); ++k) {
    straight[k] =
        moving_[k] &&
        (signals_.gyro_radps.empty() ? !turning_[k] : std::abs(signals_.gyro_radps[k]) < 0.05);
  }
  const auto span = static_cast<std::size_t>(std::lround(3.0 / signals_.step_s));
  for (std::size_t k = span; k + span < straight.size(); ++k) {
    straight_long[k] = std::all_of(straight.begin() + static_cast<std::ptrdiff_t>(k - span),
                                   straight.begin() + static_cast<std::ptrdiff_t>(k + span + 1),
                                   [](bool b) { return b; });
  }
  const bool long_baseline = count(straight_long) >= 50;
  const auto& compared = long_baseline ? straight_long : count(straight) >= 50 ? straight : moving_;
  const auto& gnss_speed = long_baseline ? signals_.gnss_speed_long_mps() : signals_.gnss_speed_mps;
  const auto ratio_of = [&](const std::vector<double>& short_speed,
                            const std::vector<double>& long_speed) {
    const auto& speed = long_baseline ? long_speed : short_speed;
    std::vector<double> ratios;
    for (std::size_t k = 0; k < speed.size(); ++k) {
      if (compared[k] && std::isfinite(speed[k]) && gnss_speed[k] > 0.0)
        ratios.push_back(speed[k] / gnss_speed[k]);
    }
    return median(std::move(ratios));
  };
  const double rl = ratio_of(signals_.speed_rl_mps, signals_.speed_long_rl_mps);
  const double rr = ratio_of(signals_.speed_rr_mps, signals_.speed_long_rr_mps);
  distance_ratio_ = 0.5 * (rl + rr);
  if (rl < 0.0 && rr < 0.0) {
    add("wheels.sign", FindingSeverity::kBlocking,
        "both rear wheels count backwards while the car drives forward",
        fmt::format("wheel speed / GNSS speed: RL {:.3f}, RR {:.3f}", rl, rr),
        "the encoders' sign convention is reversed",
        "negate both wheel columns (import map: scale: -1 on rl and rr)");
    return false;
  }
  struct Wheel {
    const char* name;  // RL, RR
    const char* id;    // rl, rr: in check names and vehicle.yaml keys
    double ratio, other_ratio, nominal_m;
  };
  for (const Wheel& wheel : {Wheel{"RL", "rl", rl, rr, facts_.vehicle.circumference_rl_m},
                             Wheel{"RR", "rr", rr, rl, facts_.vehicle.circumference_rr_m}}) {
    const auto [name, id, ratio, other_ratio, nominal] = wheel;
    if (ratio < 0.0) {
      add(fmt::format("wheels.{}_sign", id), FindingSeverity::kBlocking,
          fmt::format("the {} wheel counts backwards while the car drives forward", name),
          fmt::format("{} speed / GNSS speed {:.3f}, the other wheel {:+.3f}", name, ratio,
                      other_ratio),
          fmt::format(
              "the {} encoder's sign is flipped (or left and right are mixed up with a sign)",
              name),
          fmt::format("negate the {} wheel column (import map: {}: scale: -1)", name, id));
      ok = false;
    } else if (const auto known = known_wheel_factor(ratio, facts_.wheel_unit)) {
      const std::string fix = *known->fix
                                  ? known->fix
                                  : fmt::format("ticks_per_rev: {:g} in vehicle.yaml",
                                                *facts_.vehicle.ticks_per_rev * known->factor);
      add(fmt::format("wheels.{}_unit", id), FindingSeverity::kBlocking,
          fmt::format("the {} wheel's distance is {:.4g}x the GNSS distance", name, ratio),
          fmt::format("median speed ratio {:.4f} over {:.0f} s of driving", ratio,
                      seconds(count(moving_))),
          known->cause, fix);
    } else if (std::abs(ratio - 1.0) > 0.10) {
      const std::string key = fmt::format("circumference_{}_m", id);
      add(fmt::format("vehicle.{}_circumference", id), FindingSeverity::kBlocking,
          fmt::format("the nominal {} circumference is {:.1f} % off the GNSS distance", name,
                      100.0 * (ratio - 1.0)),
          fmt::format("{} {:.4f} m in vehicle.yaml; the GNSS says about {:.4f} m", key, nominal,
                      nominal / ratio),
          "a wrong tyre size, or a unit or factor not on the known list",
          fmt::format("{}: {:.4f} in vehicle.yaml (then calibrate)", key, nominal / ratio));
    }
  }
  return ok;
}

double Doctor::turn_scale(const std::vector<double>& wheels,
                          const std::vector<double>& other) const {
  double along = 0.0, magnitude = 0.0;
  std::size_t n = 0;
  for (std::size_t k = 0; k < wheels.size(); ++k) {
    if (!moving_[k] || !(std::abs(wheels[k]) > 0.1) || !std::isfinite(other[k])) continue;
    along += wheels[k] > 0.0 ? other[k] : -other[k];
    magnitude += std::abs(wheels[k]);
    ++n;
  }
  return n >= 20 ? along / magnitude : NAN;
}

void Doctor::check_yaw_rates() {
  const auto& wheels = signals_.wheel_yaw_rate_radps;
  const auto& course = signals_.gnss_course_rate_radps;
  if (count(turning_) < 50) {
    add("yaw.too_straight", FindingSeverity::kNote,
        "too little turning to check left/right, the gyro's sign and the IMU axes",
        fmt::format("{:.1f} s turning faster than 3 deg/s", seconds(count(turning_))), "", "");
    return;
  }
  const double wheel_course = correlation(wheels, course, turning_);
  const bool gyro = !signals_.gyro_radps.empty();
  const double wheel_gyro = gyro ? correlation(wheels, signals_.gyro_radps, turning_) : NAN;
  const double gyro_course = gyro ? correlation(signals_.gyro_radps, course, turning_) : NAN;
  const std::string evidence = fmt::format(
      "correlation of yaw rates: wheels-GNSS course {:+.2f}{}", wheel_course,
      gyro ? fmt::format(", wheels-gyro {:+.2f}, gyro-GNSS course {:+.2f}", wheel_gyro, gyro_course)
           : std::string());
  constexpr double kAgree = 0.3;
  if (gyro && wheel_gyro < -kAgree && gyro_course > kAgree) {
    add("wheels.swapped", FindingSeverity::kBlocking, "left and right wheels are swapped", evidence,
        "the wheels turn opposite to the gyro and the GNSS course",
        "swap rl and rr (wheels.csv columns, or the import map's rl/rr)");
  } else if (gyro && wheel_gyro < -kAgree && wheel_course > kAgree) {
    add("imu.yaw_sign", FindingSeverity::kBlocking, "the gyro's yaw rate has the wrong sign",
        evidence,
        "the IMU is forward-right-down (or mounted upside down) and was read as forward-left-up",
        "negate wz (import map: imu frame: frd)");
  } else if (wheel_course < -kAgree && (!gyro || wheel_gyro > kAgree)) {
    add("gnss.mirrored", FindingSeverity::kBlocking, "the GNSS track is mirrored", evidence,
        facts_.gnss_geodetic ? "latitude and longitude are swapped"
                             : "x and y (east and north) are swapped",
        facts_.gnss_geodetic ? "swap the lat and lon columns" : "swap the x and y columns");
  } else if (!gyro && wheel_course < -kAgree) {
    add("wheels.swapped", FindingSeverity::kBlocking, "the wheels turn opposite to the GNSS course",
        evidence, "left and right wheels swapped (or the GNSS mirrored)",
        "swap rl and rr (import map: exchange the two columns)");
  }
  if (gyro) {
    const double scale = turn_scale(wheels, signals_.gyro_radps);
    for (const auto& [factor, cause, fix] :
         {std::tuple{180.0 / kPi, "gyro rate in deg/s read as rad/s",
                     "give wz in rad/s (import map: unit: deg/s)"},
          std::tuple{kPi / 180.0, "gyro rate in rad/s read as deg/s",
                     "give wz in rad/s (import map: unit: rad/s)"}}) {
      if (std::abs(std::abs(scale) / factor - 1.0) < 0.1) {
        add("imu.yaw_unit", FindingSeverity::kBlocking, "the gyro's yaw rate is in the wrong unit",
            fmt::format("gyro / wheel yaw rate {:.4g}", scale), cause, fix);
      }
    }
  }
  if (!signals_.heading_rate_radps.empty()) {
    // The gyro unless it is the stream found turning the wrong way.
    const bool use_gyro = gyro && !has("imu.yaw_sign");
    const auto& reference = use_gyro ? signals_.gyro_radps : wheels;
    const double scale = slope_through_origin(reference, signals_.heading_rate_radps, turning_);
    if (std::abs(scale + 1.0) < 0.2) {
      add("heading.convention", FindingSeverity::kBlocking,
          "the heading stream turns the wrong way",
          fmt::format("heading rate / {} yaw rate {:.3f}", use_gyro ? "gyro" : "wheel", scale),
          "a compass heading (clockwise from north) read as ENU (counter-clockwise from east)",
          "heading = 90 deg - compass (import map: heading convention: compass_cw)");
    }
  }
}

void Doctor::check_track_width() {
  if (!(distance_ratio_ > 0.0) || has("imu.yaw_unit") || has("imu.yaw_sign") ||
      has("wheels.swapped") || has("gnss.mirrored") || has("vehicle.rl_circumference") ||
      has("vehicle.rr_circumference") || has("wheels.rl_unit") || has("wheels.rr_unit"))
    return;
  const WheelTurnScale turn = wheel_turn_scale(signals_, moving_);
  const double stated = facts_.vehicle.track_width_m;
  if (!std::isfinite(turn.at_rest) || !(stated > 0.0)) return;
  // Wheels that turn faster than the gyro roll on a wider track than stated.
  const double ratio = turn.at_rest / distance_ratio_;
  constexpr double kTolerance = 0.05, kSigmas = 5.0;
  if (std::abs(ratio - 1.0) <= kTolerance ||
      std::abs(ratio - 1.0) <= kSigmas * turn.sigma / distance_ratio_)
    return;
  add("vehicle.track_width", FindingSeverity::kWarning,
      fmt::format("the wheels roll on a track {:.1f} % {} than vehicle.yaml states",
                  100.0 * std::abs(ratio - 1.0), ratio > 1.0 ? "wider" : "narrower"),
      fmt::format("wheel / gyro yaw rate {:.3f} (1-sigma {:.3f}) at rest speed over {:.0f} s "
                  "turning, wheel / GNSS distance {:.3f}; track_width_m {:.3f} m, the wheels "
                  "say about {:.3f} m",
                  turn.at_rest, turn.sigma, seconds(turn.turning), distance_ratio_, stated,
                  stated * ratio),
      "track_width_m is not the rear track the wheels roll on (the front track, a distance "
      "between tyre edges, another car's), or the wheels slip sideways (a skid-steer robot)",
      fmt::format("track_width_m: {:.3f} in vehicle.yaml, or calibrate with "
                  "estimate_track_width: true",
                  stated * ratio));
}

}  // namespace odocal::detail
