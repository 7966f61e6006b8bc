#include "odocal/estimation/log_diagnosis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "diagnosis_facts.hpp"
#include "diagnosis_signals.hpp"
#include "diagnosis_track.hpp"
#include "doppler_scale.hpp"
#include "odocal/estimation/interpolation.hpp"
#include "odocal/estimation/median.hpp"
#include "odocal/estimation/prepared_blocks.hpp"
#include "odocal/estimation/standstill.hpp"
#include "odocal/estimation/wheel_gaps.hpp"
#include "odocal/model/angle.hpp"

namespace odocal {
namespace {

using detail::DiagnosisSignals;
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

class Doctor {
 public:
  Doctor(detail::DiagnosisFacts facts, DiagnosisSignals signals)
      : facts_(std::move(facts)), signals_(std::move(signals)) {
    moving_.resize(signals_.size());
    turning_.resize(signals_.size());
    for (std::size_t k = 0; k < signals_.size(); ++k) {
      moving_[k] = signals_.gnss_speed_mps[k] > 3.0;
      const double gyro = signals_.gyro_radps.empty() ? 0.0 : signals_.gyro_radps[k];
      turning_[k] = moving_[k] &&
                    (std::abs(signals_.wheel_yaw_rate_radps[k]) > 0.05 || std::abs(gyro) > 0.05);
    }
  }

  Diagnosis run() {
    out_.compared_s = seconds(signals_.size());
    const bool clocks_agree = check_spans();
    if (signals_.size() > 0 && clocks_agree) {
      const bool signs_ok = check_wheel_speeds();
      if (signs_ok) check_yaw_rates();
      check_clock_offsets();
      if (signs_ok) check_track_width();
      if (signs_ok) check_imu_axes();
      // The wheels were compared with the Doppler speed where there is one: in another unit it
      // makes right wheels look wrong by its factor.
      if (check_doppler_unit()) {
        std::erase_if(out_.findings, [](const Finding& f) {
          return f.check.starts_with("vehicle.") ||
                 (f.check.starts_with("wheels.") && f.check.ends_with("_unit"));
        });
      }
      // A mirrored GNSS track (lat/lon swapped) also scales its distances by direction: the
      // wheel ratios then say nothing about units or circumferences.
      if (has("gnss.mirrored")) {
        std::erase_if(out_.findings, [](const Finding& f) {
          return f.check.starts_with("vehicle.") || f.check.ends_with("_unit");
        });
      }
      // The gyro is judged against the wheels' yaw rate: wheels in a wrong unit (which the GNSS
      // confirms) make a right gyro look wrong by the same factor.
      if (has("wheels.rl_unit") || has("wheels.rr_unit")) {
        std::erase_if(out_.findings, [](const Finding& f) { return f.check == "imu.yaw_unit"; });
      }
    }
    check_gnss_repeats();
    // Stale repeated positions lag the track and distort its speed: no clock offset and no
    // circumference can be read from it until they are gone.
    if (has("gnss.repeated")) {
      std::erase_if(out_.findings, [](const Finding& f) {
        return f.check == "time.gnss_offset" || f.check.starts_with("vehicle.");
      });
    }
    check_gaps();
    check_standstill_biases();
    check_altitude();
    return std::move(out_);
  }

 private:
  void add(std::string check, FindingSeverity severity, std::string what, std::string evidence,
           std::string cause, std::string fix) {
    out_.findings.push_back({std::move(check), severity, std::move(what), std::move(evidence),
                             std::move(cause), std::move(fix)});
  }

  bool has(std::string_view check) const {
    return std::any_of(out_.findings.begin(), out_.findings.end(),
                       [&](const Finding& f) { return f.check == check; });
  }

  std::size_t count(const std::vector<bool>& use) const {
    return static_cast<std::size_t>(std::count(use.begin(), use.end(), true));
  }

  double seconds(std::size_t samples) const {
    return static_cast<double>(samples) * signals_.step_s;
  }

  // Time scale and span: the wheels' and GNSS's clocks must cover the same drive.
  bool check_spans() {
    const auto& wheels = facts_.wheels;
    const auto& gnss = facts_.gnss;
    const double wheels_s = wheels.last_s - wheels.first_s;
    const double gnss_s = gnss.last_s - gnss.first_s;
    const double ratio = gnss_s / wheels_s;
    for (const double factor : {10.0, 100.0, 1000.0, 1e6, 1e9, 60.0, 3600.0}) {
      for (const double r : {factor, 1.0 / factor}) {
        if (std::abs(ratio / r - 1.0) < 0.05) {
          add("time.scale", FindingSeverity::kBlocking,
              "the GNSS and wheel clocks run at different rates",
              fmt::format("gnss.csv spans {:.6g} s, wheels.csv {:.6g} s (x{:.4g})", gnss_s,
                          wheels_s, ratio),
              "a time column in the wrong unit (ms read as s, or s read as ms, ...)",
              fmt::format("scale the time of gnss.csv by {:g} (import map: time.unit)", 1.0 / r));
          return false;
        }
      }
    }
    const double overlap_s =
        std::min(wheels.last_s, gnss.last_s) - std::max(wheels.first_s, gnss.first_s);
    if (signals_.size() == 0 && overlap_s > 0.0) {
      add("time.short", FindingSeverity::kNote, "too short to compare the streams",
          fmt::format("wheels and GNSS share {:.1f} s", overlap_s), "", "");
      return false;
    }
    if (signals_.size() == 0) {
      add("time.span", FindingSeverity::kBlocking, "wheels and GNSS share no time",
          fmt::format("wheels {:.3f} to {:.3f} s, GNSS {:.3f} to {:.3f} s", wheels.first_s,
                      wheels.last_s, gnss.first_s, gnss.last_s),
          "the two loggers' clocks are unrelated (different epochs)",
          "give both streams one clock (import map: time.offset_s)");
      return false;
    }
    const double shared = seconds(signals_.size());
    if (shared < 0.9 * std::min(wheels_s, gnss_s) - 2.0 ||
        shared < 0.5 * std::max(wheels_s, gnss_s)) {
      add("time.span", FindingSeverity::kWarning, "the streams cover different spans",
          fmt::format("wheels {:.1f} s, GNSS {:.1f} s, both {:.1f} s", wheels_s, gnss_s, shared),
          "a logger started late or stopped early, or its clock is offset",
          "calibration uses the shared span only; check the time columns if it should be longer");
    }
    check_optional_span("imu.csv", facts_.imu);
    check_optional_span("heading.csv", facts_.heading);
    return true;
  }

  // An IMU or heading stream that covers much less of the wheels' span than the wheels do: the
  // reference has no gyro or heading for the rest.
  void check_optional_span(const char* file, const detail::StreamSpan& span) {
    if (span.samples == 0) return;
    const double wheels_from = facts_.wheels.first_s, wheels_to = facts_.wheels.last_s;
    const double covered = std::min(wheels_to, span.last_s) - std::max(wheels_from, span.first_s);
    const double wheels_s = wheels_to - wheels_from;
    if (covered < 0.9 * wheels_s - 2.0) {
      add("time.span", FindingSeverity::kWarning, "the streams cover different spans",
          fmt::format("{} covers {:.1f} s of the wheels' {:.1f} s ({:.3f} to {:.3f} s)", file,
                      std::max(0.0, covered), wheels_s, span.first_s, span.last_s),
          "a logger started late or stopped early, or its clock is offset",
          fmt::format("the reference has no {} for the rest; check its time column", file));
    }
  }

  // Each wheel's speed against the GNSS speed: sign, unit and circumference.
  bool check_wheel_speeds() {
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
    const auto& compared = long_baseline           ? straight_long
                           : count(straight) >= 50 ? straight
                                                   : moving_;
    const auto& gnss_speed =
        long_baseline ? signals_.gnss_speed_long_mps() : signals_.gnss_speed_mps;
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

  // How many times faster `other` turns than the wheels, over clear turns of the wheels (a slope
  // would be diluted by the wheels' noise): the mean of other x sign(wheels) over the mean
  // |wheels|.
  double turn_scale(const std::vector<double>& wheels, const std::vector<double>& other) const {
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

  // Wheels, gyro and GNSS course must turn the same way at the same rate.
  void check_yaw_rates() {
    const auto& wheels = signals_.wheel_yaw_rate_radps;
    const auto& course = signals_.gnss_course_rate_radps;
    if (count(turning_) < 50) {
      add("yaw.too_straight", FindingSeverity::kNote,
          "too little turning to check left/right, the gyro's sign and the IMU axes",
          fmt::format("{:.1f} s turning faster than 3 deg/s", seconds(count(turning_))), "", "");
      return;
    }
    const double wheel_course = detail::correlation(wheels, course, turning_);
    const bool gyro = !signals_.gyro_radps.empty();
    const double wheel_gyro =
        gyro ? detail::correlation(wheels, signals_.gyro_radps, turning_) : NAN;
    const double gyro_course =
        gyro ? detail::correlation(signals_.gyro_radps, course, turning_) : NAN;
    const std::string evidence =
        fmt::format("correlation of yaw rates: wheels-GNSS course {:+.2f}{}", wheel_course,
                    gyro ? fmt::format(", wheels-gyro {:+.2f}, gyro-GNSS course {:+.2f}",
                                       wheel_gyro, gyro_course)
                         : std::string());
    constexpr double kAgree = 0.3;
    if (gyro && wheel_gyro < -kAgree && gyro_course > kAgree) {
      add("wheels.swapped", FindingSeverity::kBlocking, "left and right wheels are swapped",
          evidence, "the wheels turn opposite to the gyro and the GNSS course",
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
      add("wheels.swapped", FindingSeverity::kBlocking,
          "the wheels turn opposite to the GNSS course", evidence,
          "left and right wheels swapped (or the GNSS mirrored)",
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
          add("imu.yaw_unit", FindingSeverity::kBlocking,
              "the gyro's yaw rate is in the wrong unit",
              fmt::format("gyro / wheel yaw rate {:.4g}", scale), cause, fix);
        }
      }
    }
    if (!signals_.heading_rate_radps.empty()) {
      // The gyro unless it is the stream found turning the wrong way.
      const bool use_gyro = gyro && !has("imu.yaw_sign");
      const auto& reference = use_gyro ? signals_.gyro_radps : wheels;
      const double scale =
          detail::slope_through_origin(reference, signals_.heading_rate_radps, turning_);
      if (std::abs(scale + 1.0) < 0.2) {
        add("heading.convention", FindingSeverity::kBlocking,
            "the heading stream turns the wrong way",
            fmt::format("heading rate / {} yaw rate {:.3f}", use_gyro ? "gyro" : "wheel", scale),
            "a compass heading (clockwise from north) read as ENU (counter-clockwise from east)",
            "heading = 90 deg - compass (import map: heading convention: compass_cw)");
      }
    }
  }

  // The wheels' forward acceleration over the second around each row: the difference of their
  // one-second mean speeds half a second either side, centred as the accelerometer's mean is.
  std::vector<double> wheel_acceleration() const {
    const auto half = static_cast<std::size_t>(std::lround(0.5 / signals_.step_s));
    std::vector<double> acceleration(signals_.size(), std::numeric_limits<double>::quiet_NaN());
    for (std::size_t k = half; half > 0 && k + half < signals_.size(); ++k) {
      const auto speed = [&](std::size_t i) {
        return 0.5 * (signals_.speed_rl_mps[i] + signals_.speed_rr_mps[i]);
      };
      acceleration[k] =
          (speed(k + half) - speed(k - half)) / (2.0 * static_cast<double>(half) * signals_.step_s);
    }
    return acceleration;
  }

  // Clock offsets between streams, from the cross-correlation of what both measure.
  void check_clock_offsets() {
    constexpr double kMaxLagS = 5.0, kMinOffsetS = 0.15;
    std::vector<double> wheel_speed(signals_.size());
    for (std::size_t k = 0; k < signals_.size(); ++k)
      wheel_speed[k] =
          0.5 * (std::abs(signals_.speed_rl_mps[k]) + std::abs(signals_.speed_rr_mps[k]));
    // A stronger anti-correlation means the signals disagree in sign (swapped wheels, a negated
    // gyro): their best positive match is then a spurious lag, not a clock. A peak hardly above
    // the zero-lag correlation is the vehicle's own dynamics (the course trails the heading
    // through a turn by its side slip), not a clock.
    const auto shows_offset = [](const detail::Lag& lag) {
      return std::isfinite(lag.lag_s) && lag.peak >= 0.5 && lag.peak > -lag.trough &&
             std::abs(lag.lag_s) >= kMinOffsetS && lag.peak - lag.at_zero >= 0.02;
    };
    const auto report = [&](const char* check, const char* stream, const detail::Lag& lag) {
      if (!shows_offset(lag)) return;
      add(check, FindingSeverity::kBlocking,
          fmt::format("the {} clock is offset from the wheels' by {:+.2f} s", stream, lag.lag_s),
          fmt::format("cross-correlation peaks at {:+.2f} s ({:.2f}; {:.2f} at zero lag)",
                      lag.lag_s, lag.peak, lag.at_zero),
          "two loggers on different clocks, or a latency not taken out",
          fmt::format("time.offset_s: {:+.3f} for {} in the import map", -lag.lag_s, stream));
      out_.findings.back().estimate = lag.lag_s;
    };
    // The GNSS clock from two signals that must agree: the speeds alone would read drive slip
    // (wheels run ahead while accelerating) as a lag, the course rate alone is noisy.
    const detail::Lag by_speed = detail::cross_correlation_lag(wheel_speed, signals_.gnss_speed_mps,
                                                               signals_.step_s, kMaxLagS);
    std::vector<double> course = signals_.gnss_course_rate_radps;
    for (double& v : course) v = std::isfinite(v) ? v : 0.0;
    const detail::Lag by_course = detail::cross_correlation_lag(signals_.wheel_yaw_rate_radps,
                                                                course, signals_.step_s, kMaxLagS);
    // Yaw rates carry a clock only where the car turns.
    const bool turns = count(turning_) >= 50;
    if (turns && std::isfinite(by_course.lag_s) && by_course.peak > 0.5) {
      if (std::abs(by_course.lag_s - by_speed.lag_s) < 0.3 || !std::isfinite(by_speed.lag_s))
        report("time.gnss_offset", "GNSS", by_course);
    } else if (std::abs(by_speed.lag_s) > 3 * kMinOffsetS) {
      report("time.gnss_offset", "GNSS", by_speed);
    }
    // A slow robot never passes the car-scale motion gate above; its gyro says when it turns.
    const std::size_t gyro_turning = static_cast<std::size_t>(
        std::count_if(signals_.gyro_radps.begin(), signals_.gyro_radps.end(),
                      [](double w) { return std::abs(w) > 0.1; }));
    if ((turns || gyro_turning >= 100) && !signals_.gyro_radps.empty()) {
      // The IMU's clock from two signals that must agree, as the GNSS's: the yaw rates alone
      // read a rear-driven car's inner wheel, spinning out of every corner, as a lag (3 laps of
      // Hockenheim: +1.0 s, 0.85 against 0.82 at zero lag). Its forward acceleration against
      // the wheels' judges, where it varies enough to say anything.
      const detail::Lag by_yaw = detail::cross_correlation_lag(
          signals_.wheel_yaw_rate_radps, signals_.gyro_radps, signals_.step_s, kMaxLagS);
      const detail::Lag by_acceleration = detail::cross_correlation_lag(
          wheel_acceleration(), signals_.ax_mps2, signals_.step_s, kMaxLagS);
      if (!(std::isfinite(by_acceleration.lag_s) && by_acceleration.peak > 0.5) ||
          std::abs(by_yaw.lag_s - by_acceleration.lag_s) < 0.3) {
        report("time.imu_offset", "IMU", by_yaw);
      } else if (shows_offset(by_yaw) || shows_offset(by_acceleration)) {
        // Disagreeing, neither is the clock's for sure: said, not blocked.
        add("time.imu_offset", FindingSeverity::kWarning,
            "the IMU clock cannot be checked against the wheels'",
            fmt::format("the yaw rates' cross-correlation peaks at {:+.2f} s ({:.2f}; {:.2f} at "
                        "zero lag), the forward accelerations' at {:+.2f} s ({:.2f}; {:.2f})",
                        by_yaw.lag_s, by_yaw.peak, by_yaw.at_zero, by_acceleration.lag_s,
                        by_acceleration.peak, by_acceleration.at_zero),
            "a driven wheel spinning out of the corners (its yaw rate trails them), or an IMU "
            "clock offset",
            "none for a car driven hard on a driven rear axle; otherwise time.offset_s for IMU "
            "in the import map");
      }
    }
  }

  // The lateral acceleration in a turn is speed x yaw rate, to the left.
  void check_imu_axes() {
    if (signals_.gyro_radps.empty() || count(turning_) < 50) return;
    // The wheels' yaw rate unless they are the ones found swapped.
    const auto& yaw_rate =
        has("wheels.swapped") ? signals_.gyro_radps : signals_.wheel_yaw_rate_radps;
    std::vector<double> centripetal(signals_.size());
    for (std::size_t k = 0; k < signals_.size(); ++k)
      centripetal[k] = signals_.gnss_speed_mps[k] * yaw_rate[k];
    const double with_ay = detail::correlation(centripetal, signals_.ay_mps2, turning_);
    const double with_ax = detail::correlation(centripetal, signals_.ax_mps2, turning_);
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

  // The Doppler column against the positions' own speed over the 4 s baseline, driving straight
  // (a chord cuts a turn short) above 5 m/s (the positions' noise then biases their speed by well
  // under a per cent). Returns whether it found the column in another unit.
  bool check_doppler_unit() {
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

  void check_gnss_repeats() {
    const std::size_t repeated = facts_.gnss_repeated, first = facts_.gnss_first_repeated_row;
    const double share =
        facts_.gnss.samples > 1 ? double(repeated) / double(facts_.gnss.samples - 1) : 0.0;
    // Standing still repeats a fix legitimately; a quarter of all rows is more than that.
    if (share > 0.25) {
      add("gnss.repeated", FindingSeverity::kBlocking, "GNSS fixes are repeated on many rows",
          fmt::format("{:.0f} % of rows repeat the previous position (first at row {})",
                      100 * share, first + 1),
          "the GNSS was logged faster than the receiver makes fixes: each fix counts several times "
          "and the sigma is too small",
          "keep only the rows where the fix changes (or log at the receiver's rate)");
    }
  }

  void check_gaps() {
    const auto& gaps = facts_.wheel_gaps;
    if (!gaps.empty()) {
      const auto longest = std::max_element(
          gaps.begin(), gaps.end(),
          [](const WheelGap& a, const WheelGap& b) { return a.duration_s < b.duration_s; });
      add("wheels.gaps", FindingSeverity::kWarning,
          fmt::format("{} gap(s) in the wheel stream", gaps.size()),
          fmt::format("longest {:.2f} s at {:.1f} s", longest->duration_s, longest->start_s),
          "dropped packets or a logger pause",
          "none needed: the odometry chain restarts at each gap");
    }
    if (facts_.gnss_gap) {
      const auto [longest, typical] = *facts_.gnss_gap;
      add("gnss.gaps", FindingSeverity::kNote, "the GNSS has gaps",
          fmt::format("longest {:.1f} s (fixes every {:.3g} s)", longest, typical),
          "an outage (tunnel, garage) or dropped messages", "none needed");
    }
  }

  void check_standstill_biases() {
    if (!facts_.standing) return;
    if (facts_.imu.samples > 0) {
      const double sum = facts_.gyro_standing_sum, sum_squares = facts_.gyro_standing_sum_squares;
      const std::size_t n = facts_.gyro_standing_samples;
      // A bias, not the gyro's noise over a few standing seconds: 4 standard errors.
      const double mean = n > 0 ? sum / static_cast<double>(n) : 0.0;
      const double spread =
          n > 1 ? std::sqrt(std::max(0.0, (sum_squares - sum * mean) / static_cast<double>(n - 1)))
                : 0.0;
      const double standard_error = n > 0 ? spread / std::sqrt(static_cast<double>(n)) : 0.0;
      if (n > 10 && std::abs(mean) > std::max(rad_from_deg(0.2), 4.0 * standard_error)) {
        add("imu.gyro_bias", FindingSeverity::kNote, "the gyro has a zero-rate bias",
            fmt::format("{:+.3f} deg/s at standstill ({} samples, standard error {:.3f} deg/s)",
                        deg_from_rad(mean), n, deg_from_rad(standard_error)),
            "an uncalibrated gyro", "none needed: the reference filter estimates it");
      }
    }
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

  void check_altitude() {
    if (!facts_.gnss_altitude) {
      add("gnss.altitude", FindingSeverity::kNote, "the GNSS has no altitude",
          "gnss.csv has no alt column",
          "on hills the 3-D path is longer than the planar one and biases the circumferences",
          "log the altitude (gnss alt column) if the drive is not flat");
    }
  }

  // The track the wheels roll on, from their yaw rate against the gyro's at rest speed, the
  // circumferences' scale (wheel against GNSS distance) taken out. Only where nothing else
  // scales the wheels' or the gyro's turn (a unit, a sign, a circumference far off).
  void check_track_width() {
    if (!(distance_ratio_ > 0.0) || has("imu.yaw_unit") || has("imu.yaw_sign") ||
        has("wheels.swapped") || has("gnss.mirrored") || has("vehicle.rl_circumference") ||
        has("vehicle.rr_circumference") || has("wheels.rl_unit") || has("wheels.rr_unit"))
      return;
    const detail::WheelTurnScale turn = detail::wheel_turn_scale(signals_, moving_);
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

  detail::DiagnosisFacts facts_;
  DiagnosisSignals signals_;
  std::vector<bool> moving_, turning_;
  double distance_ratio_ = std::numeric_limits<double>::quiet_NaN();  // wheels / GNSS, straight
  Diagnosis out_;
};

}  // namespace

bool Diagnosis::blocking() const {
  return std::any_of(findings.begin(), findings.end(),
                     [](const Finding& f) { return f.severity == FindingSeverity::kBlocking; });
}

const char* severity_name(FindingSeverity severity) {
  switch (severity) {
    case FindingSeverity::kBlocking:
      return "blocking";
    case FindingSeverity::kWarning:
      return "warning";
    case FindingSeverity::kNote:
      return "note";
  }
  return "?";
}

std::string describe(const Finding& finding) {
  std::string line =
      fmt::format("[{}] {}: {}", severity_name(finding.severity), finding.what, finding.evidence);
  if (!finding.cause.empty()) line += "; likely " + finding.cause;
  if (!finding.fix.empty()) line += "; fix: " + finding.fix;
  return line + " (" + finding.check + ")";
}

Diagnosis diagnose_log(LogBlockSource& source) {
  DiagnosisSignals signals;
  detail::DiagnosisFacts facts = detail::diagnosis_facts(source, signals);
  return Doctor(std::move(facts), std::move(signals)).run();
}

Diagnosis diagnose_log(const Log& log) {
  InMemoryLogSource source(log);
  return diagnose_log(source);
}

}  // namespace odocal
