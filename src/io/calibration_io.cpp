#include "odocal/io/calibration_io.hpp"

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "odocal/error.hpp"
#include "yaml_map.hpp"

namespace odocal {
namespace {

using detail::YamlMap;
using nlohmann::json;

void read_diagonal(YamlMap& map, const std::string& key, Eigen::Vector3d& value) {
  const auto items = map.sequence(key);
  if (items.empty()) return;
  if (items.size() != 3)
    throw InputError(map.location(key), "expected a list of 3 positive numbers");
  for (int i = 0; i < 3; ++i) {
    try {
      value(i) = items[static_cast<std::size_t>(i)].as<double>();
    } catch (const YAML::Exception&) {
      throw InputError(map.location(key), "expected a list of 3 positive numbers");
    }
    if (!(value(i) > 0.0) || !std::isfinite(value(i))) {
      throw InputError(map.location(key), "expected a list of 3 positive numbers");
    }
  }
}

void read_batch_options(YamlMap& map, BatchOptions& b) {
  map.read("keyframe_interval_s", b.keyframe_interval_s, 1e-3, 1e4);
  map.read("slip_sigma_m_per_sqrt_m", b.slip_sigma_m_per_sqrt_m, 0.0, 1.0);
  map.read("quantisation_sigma_rev", b.quantisation_sigma_rev, -1.0, 1.0);
  map.read("lateral_sigma_m_per_sqrt_m", b.lateral_sigma_m_per_sqrt_m, 0.0, 1.0);
  map.read("gnss_gauss_markov_sigma_m", b.gnss_gauss_markov_sigma_m, 0.0, 1e3);
  map.read("gnss_gauss_markov_tau_s", b.gnss_gauss_markov_tau_s, 1e-3, 1e6);
  std::string loss = robust_loss_name(b.gnss_loss);
  map.read("gnss_loss", loss);
  bool known = false;
  for (const RobustLoss candidate : {RobustLoss::kNone, RobustLoss::kHuber, RobustLoss::kCauchy}) {
    if (loss == robust_loss_name(candidate)) {
      b.gnss_loss = candidate;
      known = true;
    }
  }
  if (!known) throw InputError(map.location("gnss_loss"), "expected none, huber or cauchy");
  map.read("gnss_loss_scale", b.gnss_loss_scale, 1e-3, 1e3);
  map.read("use_heading", b.use_heading);
  map.read("use_gyro", b.use_gyro);
  map.read("estimate_track_width", b.estimate_track_width);
  map.read("estimate_gyro_bias", b.estimate_gyro_bias);
  map.read("estimate_heading_bias", b.estimate_heading_bias);
  map.read("estimate_lever_arm", b.estimate_lever_arm);
  map.read("estimate_latency", b.estimate_latency);
  map.read("max_solver_iterations", b.max_solver_iterations, 1, 100000);
  map.read("relinearise_relative_change", b.relinearise_relative_change, 1e-12, 1.0);
  map.read("max_relinearisations", b.max_relinearisations, 0, 100);
  map.read("max_sigma_circumference_m", b.max_sigma_circumference_m, 0.0, 1.0);
  map.read("max_sigma_track_width_m", b.max_sigma_track_width_m, 0.0, 1.0);
  map.read("max_sigma_gyro_bias_radps", b.max_sigma_gyro_bias_radps, 0.0, 1.0);
  map.read("max_sigma_heading_bias_rad", b.max_sigma_heading_bias_rad, 0.0, 10.0);
  map.read("max_sigma_lever_arm_m", b.max_sigma_lever_arm_m, 0.0, 100.0);
  map.read("max_sigma_latency_s", b.max_sigma_latency_s, 0.0, 100.0);
  map.reject_unknown_keys();
}

json batch_options_to_json(const BatchOptions& b) {
  return {{"keyframe_interval_s", b.keyframe_interval_s},
          {"slip_sigma_m_per_sqrt_m", b.slip_sigma_m_per_sqrt_m},
          {"quantisation_sigma_rev", b.quantisation_sigma_rev},
          {"lateral_sigma_m_per_sqrt_m", b.lateral_sigma_m_per_sqrt_m},
          {"gnss_gauss_markov_sigma_m", b.gnss_gauss_markov_sigma_m},
          {"gnss_gauss_markov_tau_s", b.gnss_gauss_markov_tau_s},
          {"gnss_loss", robust_loss_name(b.gnss_loss)},
          {"gnss_loss_scale", b.gnss_loss_scale},
          {"use_heading", b.use_heading},
          {"use_gyro", b.use_gyro},
          {"estimate_track_width", b.estimate_track_width},
          {"estimate_gyro_bias", b.estimate_gyro_bias},
          {"estimate_heading_bias", b.estimate_heading_bias},
          {"estimate_lever_arm", b.estimate_lever_arm},
          {"estimate_latency", b.estimate_latency},
          {"max_solver_iterations", b.max_solver_iterations},
          {"relinearise_relative_change", b.relinearise_relative_change},
          {"max_relinearisations", b.max_relinearisations},
          {"max_sigma_circumference_m", b.max_sigma_circumference_m},
          {"max_sigma_track_width_m", b.max_sigma_track_width_m},
          {"max_sigma_gyro_bias_radps", b.max_sigma_gyro_bias_radps},
          {"max_sigma_heading_bias_rad", b.max_sigma_heading_bias_rad},
          {"max_sigma_lever_arm_m", b.max_sigma_lever_arm_m},
          {"max_sigma_latency_s", b.max_sigma_latency_s}};
}

json summary_to_json(const DeadReckoningSummary& s) {
  return {{"mean_position_m", s.mean_position_m},
          {"max_position_m", s.max_position_m},
          {"mean_heading_deg", s.mean_heading_rad * 180.0 / M_PI},
          {"max_heading_deg", s.max_heading_rad * 180.0 / M_PI}};
}

json vector_json(const Eigen::Vector3d& v) { return json::array({v(0), v(1), v(2)}); }

}  // namespace

std::optional<CalibrationMethod> parse_method(const std::string& name) {
  for (auto method : {CalibrationMethod::kIterative, CalibrationMethod::kFixedP,
                      CalibrationMethod::kAugmented, CalibrationMethod::kBatch}) {
    if (name == method_name(method)) return method;
  }
  return std::nullopt;
}

CalibrationOptions parse_calibration_options(const std::string& yaml_text, const std::string& file,
                                             CalibrationOptions o) {
  const YAML::Node root_node = detail::parse_yaml(yaml_text, file);
  if (root_node.IsNull()) return o;
  YamlMap root(root_node, file, "");
  std::string method = method_name(o.method);
  root.read("method", method);
  const auto parsed_method = parse_method(method);
  if (!parsed_method)
    throw InputError(root.location("method"), "expected iterative, fixed-p, augmented or batch");
  o.method = *parsed_method;
  if (auto reference = root.map("reference")) {
    std::string mode = o.reference.mode == ReferenceMode::kFilter ? "filter" : "smoother";
    reference->read("mode", mode);
    if (mode != "filter" && mode != "smoother")
      throw InputError(reference->location("mode"), "expected filter or smoother");
    o.reference.mode = mode == "filter" ? ReferenceMode::kFilter : ReferenceMode::kSmoother;
    reference->read("gnss_sigma_m", o.reference.gnss_sigma_m, 1e-6, 1e4);
    reference->read("heading_sigma_rad", o.reference.heading_sigma_rad, 1e-6, 10.0);
    reference->read("acc_sigma_mps2", o.reference.acc_sigma_mps2, 1e-6, 100.0);
    reference->read("yaw_rate_sigma_radps", o.reference.yaw_rate_sigma_radps, 1e-6, 10.0);
    reference->read("acc_random_walk_mps2", o.reference.acc_random_walk_mps2, 0.0, 100.0);
    reference->read("yaw_random_walk_radps", o.reference.yaw_random_walk_radps, 0.0, 10.0);
    reference->read("no_imu_acc_psd", o.reference.no_imu_acc_psd, 1e-6, 1e4);
    reference->read("no_imu_yaw_rate_psd", o.reference.no_imu_yaw_rate_psd, 1e-6, 100.0);
    reference->read("course_min_speed_mps", o.reference.course_min_speed_mps, 0.0, 100.0);
    reference->read("course_sigma_rad", o.reference.course_sigma_rad, 1e-6, 10.0);
    reference->read("gnss_gate_chi2", o.reference.gnss_gate_chi2, 0.0, 1e6);
    reference->read("use_gnss_speed", o.reference.use_gnss_speed);
    reference->read("gnss_speed_sigma_mps", o.reference.gnss_speed_sigma_mps, 1e-6, 100.0);
    reference->read("gnss_speed_min_mps", o.reference.gnss_speed_min_mps, 0.0, 100.0);
    reference->reject_unknown_keys();
  }
  read_diagonal(root, "measurement_diagonal", o.measurement_diagonal);
  root.read("decay_exponent_q", o.decay_exponent_q, 1.0, 2.0);
  read_diagonal(root, "fixed_process_diagonal", o.fixed_process_diagonal);
  read_diagonal(root, "ls_weights", o.ls_weights);
  root.read("ls_window_samples", o.ls_window_samples, 1, 100000);
  root.read("max_iterations", o.max_iterations, 1, 10000);
  root.read("patience", o.patience, 1, 10000);
  root.read("heading_weight_m_per_rad", o.heading_weight_m_per_rad, 0.0, 1e6);
  std::string start = o.dr_start == DeadReckoningStart::kFirstReference  ? "first-reference"
                      : o.dr_start == DeadReckoningStart::kAlignedWindow ? "aligned-window"
                                                                         : "aligned-whole";
  root.read("dr_start", start);
  if (start == "first-reference")
    o.dr_start = DeadReckoningStart::kFirstReference;
  else if (start == "aligned-window")
    o.dr_start = DeadReckoningStart::kAlignedWindow;
  else if (start == "aligned-whole")
    o.dr_start = DeadReckoningStart::kAlignedWhole;
  else
    throw InputError(root.location("dr_start"),
                     "expected first-reference, aligned-window or aligned-whole");
  root.read("dr_align_window_s", o.dr_align_window_s, 1.0, 1e6);
  if (auto augmented = root.map("augmented")) {
    read_diagonal(*augmented, "pose_process_diagonal", o.augmented_pose_process_diagonal);
    augmented->read("param_sigma_m_per_step", o.augmented_param_sigma_m_per_step, 0.0, 1.0);
    augmented->read("initial_param_sigma_m", o.augmented_initial_param_sigma_m, 1e-9, 1.0);
    augmented->reject_unknown_keys();
  }
  if (auto batch = root.map("batch")) read_batch_options(*batch, o.batch);
  root.read("min_distance_m", o.min_distance_m, 0.0, 1e9);
  double min_samples = static_cast<double>(o.min_reference_samples);
  root.read("min_reference_samples", min_samples, 2.0, 1e9);
  o.min_reference_samples = static_cast<std::size_t>(min_samples);
  root.read("max_condition_number", o.max_condition_number, 1.0, 1e300);
  root.read("min_heading_range_for_difference_rad", o.min_heading_range_for_difference_rad, 0.0,
            1e3);
  root.reject_unknown_keys();
  return o;
}

CalibrationOptions read_calibration_options(const std::string& path, CalibrationOptions defaults) {
  std::ifstream stream(path);
  if (!stream) throw InputError({path, 0, ""}, "cannot open file");
  std::ostringstream text;
  text << stream.rdbuf();
  return parse_calibration_options(text.str(), path, defaults);
}

json options_to_json(const CalibrationOptions& o) {
  return {{"method", method_name(o.method)},
          {"reference",
           {{"mode", o.reference.mode == ReferenceMode::kFilter ? "filter" : "smoother"},
            {"gnss_sigma_m", o.reference.gnss_sigma_m},
            {"heading_sigma_rad", o.reference.heading_sigma_rad},
            {"acc_sigma_mps2", o.reference.acc_sigma_mps2},
            {"yaw_rate_sigma_radps", o.reference.yaw_rate_sigma_radps},
            {"acc_random_walk_mps2", o.reference.acc_random_walk_mps2},
            {"yaw_random_walk_radps", o.reference.yaw_random_walk_radps},
            {"no_imu_acc_psd", o.reference.no_imu_acc_psd},
            {"no_imu_yaw_rate_psd", o.reference.no_imu_yaw_rate_psd},
            {"course_min_speed_mps", o.reference.course_min_speed_mps},
            {"course_sigma_rad", o.reference.course_sigma_rad},
            {"gnss_gate_chi2", o.reference.gnss_gate_chi2},
            {"use_gnss_speed", o.reference.use_gnss_speed},
            {"gnss_speed_sigma_mps", o.reference.gnss_speed_sigma_mps},
            {"gnss_speed_min_mps", o.reference.gnss_speed_min_mps}}},
          {"measurement_diagonal", vector_json(o.measurement_diagonal)},
          {"decay_exponent_q", o.decay_exponent_q},
          {"fixed_process_diagonal", vector_json(o.fixed_process_diagonal)},
          {"ls_weights", vector_json(o.ls_weights)},
          {"ls_window_samples", o.ls_window_samples},
          {"max_iterations", o.max_iterations},
          {"patience", o.patience},
          {"heading_weight_m_per_rad", o.heading_weight_m_per_rad},
          {"dr_start", o.dr_start == DeadReckoningStart::kFirstReference  ? "first-reference"
                       : o.dr_start == DeadReckoningStart::kAlignedWindow ? "aligned-window"
                                                                          : "aligned-whole"},
          {"dr_align_window_s", o.dr_align_window_s},
          {"augmented",
           {{"pose_process_diagonal", vector_json(o.augmented_pose_process_diagonal)},
            {"param_sigma_m_per_step", o.augmented_param_sigma_m_per_step},
            {"initial_param_sigma_m", o.augmented_initial_param_sigma_m}}},
          {"batch", batch_options_to_json(o.batch)},
          {"min_distance_m", o.min_distance_m},
          {"min_reference_samples", o.min_reference_samples},
          {"max_condition_number", o.max_condition_number},
          {"min_heading_range_for_difference_rad", o.min_heading_range_for_difference_rad}};
}

json result_to_json(const CalibrationResult& r, const CalibrationOptions& options) {
  json iterations = json::array();
  for (const IterationRecord& it : r.iterations) {
    iterations.push_back({{"iteration", it.iteration},
                          {"circumference_rl_m", it.circumference_rl_m},
                          {"circumference_rr_m", it.circumference_rr_m},
                          {"score", it.score},
                          {"errors", summary_to_json(it.errors)}});
  }
  json out = {
      {"method", method_name(r.method)},
      {"circumference_rl_m", r.estimate.circumference_rl_m},
      {"circumference_rr_m", r.estimate.circumference_rr_m},
      {"track_width_m", r.estimate.track_width_m},
      {"sigma_circumference_rl_m", std::sqrt(r.covariance(0, 0))},
      {"sigma_circumference_rr_m", std::sqrt(r.covariance(1, 1))},
      {"covariance_m2",
       {{r.covariance(0, 0), r.covariance(0, 1)}, {r.covariance(1, 0), r.covariance(1, 1)}}},
      {"condition_number", r.condition_number},
      {"nominal",
       {{"circumference_rl_m", r.nominal.circumference_rl_m},
        {"circumference_rr_m", r.nominal.circumference_rr_m},
        {"track_width_m", r.nominal.track_width_m}}},
      {"chosen_iteration", r.chosen_iteration},
      {"iterations", iterations},
      {"dead_reckoning_before", summary_to_json(r.before)},
      {"dead_reckoning_after", summary_to_json(r.after)},
      {"distance_m", r.distance_m},
      {"reference_samples", r.reference_samples},
      {"reference_heading_source", r.reference_heading_source},
      {"termination", r.termination},
      {"configuration", options_to_json(options)}};
  if (!r.parameter_t_s.empty()) {
    out["parameter_series"] = {{"t_s", r.parameter_t_s},
                               {"circumference_rl_m", r.parameter_c_rl_m},
                               {"circumference_rr_m", r.parameter_c_rr_m}};
  }
  if (!r.parameters.empty()) {
    json parameters = json::array();
    for (const EstimatedParameter& p : r.parameters) {
      json entry = {{"name", p.name}, {"value", p.value}, {"estimated", p.estimated}};
      if (p.estimated) {  // an infinite sigma (not computable) is written as null
        entry["sigma"] = std::isfinite(p.sigma) ? json(p.sigma) : json(nullptr);
        entry["identified"] = p.identified;
        if (!p.verdict.empty()) entry["verdict"] = p.verdict;
      }
      parameters.push_back(entry);
    }
    out["parameters"] = parameters;
    out["identifiability"] = r.identifiability;
    out["solver_report"] = r.solver_report;
  }
  return out;
}

}  // namespace odocal
