#include "odocal/io/calibration_io.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "odocal/error.hpp"
#include "odocal/io/input_file.hpp"
#include "odocal/model/angle.hpp"
#include "option_fields_io.hpp"
#include "yaml_map.hpp"

namespace odocal {
namespace {

using detail::YamlMap;
using nlohmann::json;

json errors_json(const DeadReckoningSummary& s) {
  return {{"mean_position_m", s.mean_position_m},
          {"max_position_m", s.max_position_m},
          {"mean_heading_deg", deg_from_rad(s.mean_heading_rad)},
          {"max_heading_deg", deg_from_rad(s.max_heading_rad)}};
}

json preparation_json(const LogPreparation& p) {
  json standstills = json::array();
  for (const Standstill& still : p.standstills)
    standstills.push_back({{"start_s", still.start_s}, {"end_s", still.end_s}});
  json gaps = json::array();
  for (const WheelGap& gap : p.wheel_gaps)
    gaps.push_back({{"start_s", gap.start_s}, {"duration_s", gap.duration_s}});
  json out = {{"standstills", standstills}, {"wheel_gaps", gaps}};
  if (p.wheel_rate_bias) {
    out["wheel_rate_bias_deg_per_s"] = {{"rl", 360.0 * p.wheel_rate_bias->rl_rev_per_s},
                                        {"rr", 360.0 * p.wheel_rate_bias->rr_rev_per_s}};
  }
  if (const auto& offset = p.accelerometer_offset) {
    out["accelerometer_offset"] = {{"forward_mps2", offset->forward_mps2},
                                   {"sigma_mps2", offset->sigma_mps2},
                                   {"stops", offset->stops},
                                   {"standing_s", offset->standing_s},
                                   {"removed", offset->removed}};
  }
  if (const auto& drive = p.drive_forward_offset) {
    out["accelerometer_drive_offset"] = {{"forward_mps2", drive->forward_mps2},
                                         {"sigma_mps2", drive->sigma_mps2},
                                         {"duration_s", drive->duration_s},
                                         {"distance_m", drive->distance_m},
                                         {"removed", drive->removed}};
  }
  if (p.driving_forward_offset_mps2)
    out["accelerometer_driving_offset_mps2"] = *p.driving_forward_offset_mps2;
  if (p.started_at_s) out["used_from_s"] = *p.started_at_s;
  return out;
}

// Infinite or NaN numbers (a sigma that could not be computed) are written as null.
json number_or_null(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

json model_adequacy_json(const ModelAdequacy& m) {
  json dependences = json::array();
  for (const ResidualDependence& d : m.dependences) {
    dependences.push_back({{"residual", d.residual},
                           {"quantity", d.quantity},
                           {"correlation", d.correlation},
                           {"t_statistic", d.t_statistic}});
  }
  return {{"intervals", m.intervals},
          {"chi2_per_dof", number_or_null(m.chi2_per_dof)},
          {"autocorrelation", number_or_null(m.autocorrelation)},
          {"dependences", dependences},
          {"judged", m.judged},
          {"explains", m.judged ? json(m.explains) : json(nullptr)},
          {"verdict", m.verdict}};
}

json core_json(const CalibrationSummary& s, const CalibrationConfig& config) {
  const Eigen::Matrix2d& P = s.covariance;
  json out = {{"method", method_name(s.method)},
              {"termination", enum_name(s.termination)},
              {"usable", s.usable()},
              {"message", s.message},
              {"note", s.note},
              {"circumference_rl_m", number_or_null(s.estimate.circumference_rl_m)},
              {"circumference_rr_m", number_or_null(s.estimate.circumference_rr_m)},
              {"track_width_m", number_or_null(s.estimate.track_width_m)},
              {"sigma_circumference_rl_m", number_or_null(s.sigma_rl_m())},
              {"sigma_circumference_rr_m", number_or_null(s.sigma_rr_m())},
              {"covariance_m2",
               {{number_or_null(P(0, 0)), number_or_null(P(0, 1))},
                {number_or_null(P(1, 0)), number_or_null(P(1, 1))}}},
              {"condition_number", number_or_null(s.condition_number)},
              {"nominal",
               {{"circumference_rl_m", s.nominal.circumference_rl_m},
                {"circumference_rr_m", s.nominal.circumference_rr_m},
                {"track_width_m", s.nominal.track_width_m}}},
              {"difference_identifiable", s.difference_identifiable},
              {"identifiability", s.identifiability},
              {"dead_reckoning_before", errors_json(s.before)},
              {"dead_reckoning_after", errors_json(s.after)},
              {"accelerometer_walk",
               {{"noise_x_mps2", s.accelerometer_walk.noise_x_mps2},
                {"noise_y_mps2", s.accelerometer_walk.noise_y_mps2},
                {"heading_deg", deg_from_rad(s.accelerometer_walk.heading_rad)}}},
              {"distance_m", s.distance_m},
              {"preparation", preparation_json(s.preparation)},
              {"coverage",
               {{"distance_m", s.coverage.distance_m},
                {"moving_s", s.coverage.moving_s},
                {"left_turning_deg", deg_from_rad(s.coverage.left_turning_rad)},
                {"right_turning_deg", deg_from_rad(s.coverage.right_turning_rad)},
                {"turning_source", s.coverage.turning_source},
                {"mean_square_speed_m2ps2", s.coverage.mean_square_speed_m2ps2()}}},
              {"reference_samples", s.reference_samples},
              {"reference_heading_source", s.reference_heading_source},
              {"configuration", config_to_json(config)}};
  if (!s.model_adequacy.verdict.empty())
    out["model_adequacy"] = model_adequacy_json(s.model_adequacy);
  out["misfit_sigma_scale"] = s.misfit_sigma_scale;
  if (s.track_sigma_m[0] > 0.0 || s.track_sigma_m[1] > 0.0) {
    out["track_sigma_m"] = {s.track_sigma_m[0], s.track_sigma_m[1]};
    out["track_width_uncertainty"] = s.track_width_uncertainty;
    out["track_share_worth_naming"] = s.track_share_worth_naming();
    out["track_under_prior"] = s.track_under_prior;
    if (std::isfinite(s.judged_track_m)) {
      out["judged_track_m"] = s.judged_track_m;
      out["judged_track_sigma_m"] = s.judged_track_sigma_m;
    }
  }
  return out;
}

void add_details(json& out, const IterativeSummary& s) {
  json iterations = json::array();
  for (const IterationRecord& it : s.iterations) {
    iterations.push_back({{"iteration", it.iteration},
                          {"circumference_rl_m", it.circumference_rl_m},
                          {"circumference_rr_m", it.circumference_rr_m},
                          {"score", it.score},
                          {"errors", errors_json(it.errors)}});
  }
  out["chosen_iteration"] = s.chosen_iteration;
  out["iterations"] = iterations;
}

void add_details(json& out, const AugmentedSummary& s) {
  out["parameter_series"] = {{"t_s", s.parameter_t_s},
                             {"circumference_rl_m", s.parameter_c_rl_m},
                             {"circumference_rr_m", s.parameter_c_rr_m}};
}

void add_details(json& out, const BatchSummary& s) {
  json parameters = json::array();
  for (const EstimatedParameter& p : s.parameters) {
    json entry = {{"name", p.name}, {"value", number_or_null(p.value)}, {"estimated", p.estimated}};
    if (p.estimated) {
      entry["sigma"] = number_or_null(p.sigma);
      entry["identified"] = p.identified;
      if (!p.verdict.empty()) entry["verdict"] = p.verdict;
    }
    parameters.push_back(entry);
  }
  out["parameters"] = parameters;
  json covariance = json::array();
  for (int r = 0; r < 3; ++r) {
    json row = json::array();
    for (int c = 0; c < 3; ++c) row.push_back(number_or_null(s.params_covariance(r, c)));
    covariance.push_back(row);
  }
  out["params_covariance_m2"] = covariance;  // of [c_RL, c_RR, t_R]
  if (s.odometry_scales) {
    const OdometryScales& o = *s.odometry_scales;
    out["odometry_scales"] = {{"speed_scale", o.speed_scale},
                              {"sigma_speed_scale", o.sigma_speed_scale},
                              {"yaw_rate_scale", o.yaw_rate_scale},
                              {"sigma_yaw_rate_scale", o.sigma_yaw_rate_scale}};
  }
  if (s.reference_circumference) {
    const ReferenceCircumference& r = *s.reference_circumference;
    out["reference_circumference"] = {{"speed_mps", r.speed_mps},
                                      {"circumference_rl_m", r.circumference_rl_m},
                                      {"circumference_rr_m", r.circumference_rr_m},
                                      {"sigma_rl_m", number_or_null(r.sigma_rl_m)},
                                      {"sigma_rr_m", number_or_null(r.sigma_rr_m)},
                                      {"identified", r.identified}};
  }
  if (s.model_spread_m[0] > 0.0 || s.model_spread_m[1] > 0.0)
    out["model_spread_m"] = {s.model_spread_m[0], s.model_spread_m[1]};
  if (s.consistency) {
    const PartsConsistency& c = *s.consistency;
    nlohmann::json parts = nlohmann::json::array();
    for (const PartsConsistency::Part& part : c.parts) {
      nlohmann::json p = {{"from_s", part.from_s}, {"to_s", part.to_s}, {"fitted", part.fitted}};
      if (part.fitted) {
        p["circumference_m"] = {part.circumference_m[0], part.circumference_m[1]};
        p["sigma_m"] = {part.sigma_m[0], part.sigma_m[1]};
      }
      parts.push_back(p);
    }
    out["consistency"] = {
        {"parts", parts},
        {"fitted_parts", c.fitted_parts},
        {"birge_ratio", {number_or_null(c.birge_ratio[0]), number_or_null(c.birge_ratio[1])}},
        {"bound", c.bound},
        {"consistent", c.consistent},
        {"sigma_scale", {c.sigma_scale[0], c.sigma_scale[1]}},
        {"verdict", c.verdict}};
  }
  if (s.latency_detection) {
    const BatchSummary::LatencyDetection& d = *s.latency_detection;
    out["latency_detection"] = {
        {"residual", d.signature.residual},
        {"correlation", d.signature.correlation},
        {"latency_s", number_or_null(d.latency_s)},
        {"sigma_s", number_or_null(d.sigma_s)},
        {"taken", d.taken},
        {"doppler_sigma_scale", d.doppler_sigma_scale},
        {"by_doppler_noise", d.by_doppler_noise},
        {"significant", d.significant},
        {"doppler_sigma_scale_with", d.doppler_sigma_scale_with},
        {"gnss_sigma_scale", d.gnss_sigma_scale},
        {"by_gnss_noise", d.by_gnss_noise},
        {"gnss_sigma_scale_with", d.gnss_sigma_scale_with},
        {"circumference_without_m", {d.circumference_without_m[0], d.circumference_without_m[1]}}};
  }
  const auto mounting_json = [](const MountingResiduals& m) {
    nlohmann::json j = nlohmann::json::object();
    if (m.gnss) {
      j["gnss_mean_m"] = {m.gnss_mean_m[0], m.gnss_mean_m[1]};
      j["gnss_standard_error_m"] = {m.gnss_standard_error_m[0], m.gnss_standard_error_m[1]};
    }
    if (m.doppler) {
      j["doppler_left_m"] = m.doppler_left_m;
      j["doppler_left_standard_error_m"] = m.doppler_left_standard_error_m;
    }
    if (m.heading) {
      j["heading_mean_rad"] = m.heading_mean_rad;
      j["heading_standard_error_rad"] = m.heading_standard_error_rad;
    }
    return j;
  };
  if (s.mounting_residuals.gnss || s.mounting_residuals.heading || s.mounting_residuals.doppler)
    out["mounting_residuals"] = mounting_json(s.mounting_residuals);
  if (s.mounting_detection) {
    const BatchSummary::MountingDetection& d = *s.mounting_detection;
    nlohmann::json j = {
        {"signature", mounting_json(d.signature)},
        {"fitted", d.fitted},
        {"taken", d.taken},
        {"circumference_without_m", {d.circumference_without_m[0], d.circumference_without_m[1]}},
        {"circumference_with_m", {d.circumference_with_m[0], d.circumference_with_m[1]}},
        {"explained_by_latency", d.explained_by_latency},
        {"by_gnss_noise", d.by_gnss_noise},
        {"found_beside_latency", d.found_beside_latency}};
    if (d.by_gnss_noise || d.found_beside_latency) {
      j["gnss_sigma_scale_without"] = d.gnss_sigma_scale_without;
      j["gnss_sigma_scale_with"] = d.gnss_sigma_scale_with;
    }
    if (d.lever_arm) {
      j["lever_arm_m"] = {d.lever_arm_m[0], d.lever_arm_m[1]};
      j["lever_arm_sigma_m"] = {d.lever_arm_sigma_m[0], d.lever_arm_sigma_m[1]};
    }
    if (d.heading_bias) {
      j["heading_bias_rad"] = d.heading_bias_rad;
      j["heading_bias_sigma_rad"] = d.heading_bias_sigma_rad;
    }
    if (const auto& after = d.heading_after) {
      j["heading_after"] = {
          {"beside_latency", after->beside_latency},
          {"seen_rad", after->seen_rad},
          {"seen_standard_error_rad", after->seen_standard_error_rad},
          {"circumference_without_m",
           {after->circumference_without_m[0], after->circumference_without_m[1]}},
          {"circumference_with_m",
           {after->circumference_with_m[0], after->circumference_with_m[1]}}};
    }
    out["mounting_detection"] = j;
  }
  if (s.body_sigma_m[0] > 0.0 || s.body_sigma_m[1] > 0.0) {
    out["body_sigma_m"] = {s.body_sigma_m[0], s.body_sigma_m[1]};
    nlohmann::json parts = nlohmann::json::object();
    for (const BatchSummary::BodySigmaPart& part : s.body_sigma_parts)
      parts[part.key] = {part.sigma_m[0], part.sigma_m[1]};
    out["body_sigma_parts_m"] = parts;
  }
  if (s.forward_offset_sigma_m[0] > 0.0 || s.forward_offset_sigma_m[1] > 0.0) {
    out["forward_offset_sigma_m"] = {s.forward_offset_sigma_m[0], s.forward_offset_sigma_m[1]};
    out["forward_offset_sigma_mps2"] = s.forward_offset_sigma_mps2;
  }
  if (s.held_sigma_m[0] > 0.0 || s.held_sigma_m[1] > 0.0) {
    out["held_sigma_m"] = {s.held_sigma_m[0], s.held_sigma_m[1]};
    nlohmann::json parts = nlohmann::json::object();
    for (const BatchSummary::HeldSigmaPart& part : s.held_sigma_parts) {
      parts[part.key] = {{"sigma_m", {part.sigma_m[0], part.sigma_m[1]}},
                         {"coefficient_sigma", part.coefficient_sigma}};
    }
    out["held_sigma_parts"] = parts;
  }
  if (s.tyre_selection.compared) {
    nlohmann::json candidates = nlohmann::json::array();
    for (const TyreCandidate& c : s.tyre_selection.candidates) {
      candidates.push_back({{"model", c.model},
                            {"bic", number_or_null(c.bic)},
                            {"solves", c.solves},
                            {"tyre", c.tyre},
                            {"every_coefficient_held", c.every_coefficient_held},
                            {"judged_under_noise_shown", c.judged_under_noise_shown},
                            {"beyond_track", c.beyond_track},
                            {"track_free", c.track_free},
                            {"held_track_bic", number_or_null(c.held_track_bic)},
                            {"free_track_bic", number_or_null(c.free_track_bic)},
                            {"held_track_score_m", number_or_null(c.held_track_score_m)},
                            {"free_track_score_m", number_or_null(c.free_track_score_m)},
                            {"needed", c.needed},
                            {"dead_reckons", c.dead_reckons},
                            {"circumference_rl_m", number_or_null(c.circumference[0])},
                            {"circumference_rr_m", number_or_null(c.circumference[1])}});
    }
    out["tyre_selection"] = {
        {"plain_bic", number_or_null(s.tyre_selection.plain_bic)},
        {"free_track_bic", number_or_null(s.tyre_selection.free_track_bic)},
        {"plain_track_free", s.tyre_selection.plain_track_free},
        {"candidates", candidates},
        {"other_solves", s.tyre_selection.other_solves},
        {"chosen", s.tyre_selection.chosen},
        {"judges_plain", s.tyre_selection.judges_plain},
        {"plain_gap_to", s.tyre_selection.plain_gap_to},
        {"plain_gap_share", s.tyre_selection.plain_gap_share},
        {"chosen_gap_to", s.tyre_selection.chosen_gap_to},
        {"chosen_gap_sigmas", number_or_null(s.tyre_selection.chosen_gap_sigmas)}};
  }
  if (s.gentle_limits) {
    out["gentle_segments"] = {{"odometry_intervals_used", s.odometry_intervals_used},
                              {"odometry_intervals", s.odometry_intervals}};
  }
  out["solver_report"] = s.solver_report;
  out["keyframes"] = s.keyframes;
  out["gnss_fixes"] = s.gnss_fixes;
  out["doppler_intervals"] = s.doppler_intervals;
  out["doppler_sigma_scale"] = s.doppler_sigma_scale;
  out["solves"] = s.solves;
  const GnssNoiseReport& g = s.gnss_noise;
  out["gnss_noise"] = {{"configured_sigma_m", g.configured_sigma_m},
                       {"residual_sigma_m", g.residual_sigma_m},
                       {"white_sigma_m", g.white_sigma_m},
                       {"gauss_markov_sigma_m", g.gauss_markov_sigma_m},
                       {"gauss_markov_tau_s", g.gauss_markov_tau_s},
                       {"adapted", g.adapted},
                       {"model_gauss_markov_sigma_m", g.model_gauss_markov_sigma_m},
                       {"model_gauss_markov_tau_s", g.model_gauss_markov_tau_s},
                       {"sigma_inflation", g.sigma_inflation},
                       {"reverted", g.reverted}};
}

}  // namespace

CalibrationConfig parse_calibration_config(const std::string& yaml_text, const std::string& file,
                                           CalibrationConfig config) {
  const YAML::Node root_node = detail::parse_yaml(yaml_text, file);
  if (root_node.IsNull()) return config;
  YamlMap root(root_node, file, "");
  for_each_config_section(config, [&](const char* section, const char*, auto table, auto& options) {
    if (*section == '\0') {
      detail::read_option_fields(root, table, options);
    } else if (auto nested = root.map(section)) {
      detail::read_option_fields(*nested, table, options);
      nested->reject_unknown_keys();
    }
  });
  root.reject_unknown_keys();
  if (const std::string problem = config.validate(); !problem.empty())
    throw InputError(root.location(), "inconsistent options: " + problem);
  return config;
}

CalibrationConfig read_calibration_config(const std::string& path, CalibrationConfig defaults) {
  return parse_calibration_config(read_input_file(path), path, defaults);
}

json config_to_json(const CalibrationConfig& config) {
  json out = json::object();
  for_each_config_section(
      config, [&](const char* section, const char*, auto table, const auto& options) {
        detail::write_option_fields(*section == '\0' ? out : out[section], table, options);
      });
  return out;
}

std::string config_to_yaml(const CalibrationConfig& config) {
  TextBuffer out;
  out.print(
      "# odocal calibrate configuration (odocal calibrate --print-config). Every key is optional;\n"
      "# a missing one keeps the value shown here. Each line: key: value  # unit, range: what.\n");
  for_each_config_section(
      config, [&](const char* section, const char* title, auto table, const auto& options) {
        out.print("\n# {}\n", title);
        const bool nested = *section != '\0';
        if (nested) out.print("{}:\n", section);
        detail::print_option_fields(out, table, options, nested ? 2 : 0);
      });
  return std::string(out.view());
}

json summary_to_json(const AnyCalibrationSummary& summary, const CalibrationConfig& config) {
  return std::visit(
      [&](const auto& s) {
        json out = core_json(s, config);
        add_details(out, s);
        return out;
      },
      summary);
}

}  // namespace odocal
