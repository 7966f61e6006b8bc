#include "odocal/estimation/batch_options.hpp"

#include <array>

namespace odocal {

OptionTable<BatchOptions> BatchOptions::fields() {
  using O = BatchOptions;
  static const std::array<OptionField<O>, 42> kFields{{
      {"keyframe_interval_s", "s", 1e-3, 1e4, "one pose unknown per this much time",
       &O::keyframe_interval_s},
      {"slip_sigma_m_per_sqrt_m", "m/sqrt(m)", 0.0, 1.0,
       "wheel slip as a random walk in arc length", &O::slip_sigma_m_per_sqrt_m},
      {"quantisation_sigma_rev", "rev", -1.0, 1.0,
       "encoder quantisation per count; negative: 1/sqrt(12) tick from ticks_per_rev; 0: exact",
       &O::quantisation_sigma_rev},
      {"heading_tick_smoothing_s", "s", 0.0, 1.0,
       "the rear wheels' tick difference (the heading) fitted with a local quadratic over +-this "
       "before the fit, their sum (the distance) as counted; 0: as counted",
       &O::heading_tick_smoothing_s},
      {"lateral_sigma_m_per_sqrt_m", "m/sqrt(m)", 0.0, 1.0,
       "side slip and model error across the course", &O::lateral_sigma_m_per_sqrt_m},
      {"gnss_gauss_markov_sigma_m", "m", 0.0, 1e3,
       "time-correlated GNSS error (first-order Gauss-Markov) per axis; 0: white only",
       &O::gnss_gauss_markov_sigma_m},
      {"gnss_gauss_markov_tau_s", "s", 1e-3, 1e6, "its correlation time",
       &O::gnss_gauss_markov_tau_s},
      {"gnss_loss", "", 0, 0, "robust loss on the GNSS residuals", enum_member<&O::gnss_loss>()},
      {"gnss_loss_scale", "sigma", 1e-3, 1e3, "where the robust loss bends, in fix sigmas",
       &O::gnss_loss_scale},
      {"adapt_gnss_noise", "", 0, 0,
       "re-solve with the GNSS noise the residuals show when it differs from the configured one",
       &O::adapt_gnss_noise},
      {"consistency_parts", "1", 0.0, 20.0,
       "calibrate the log again in this many parts and widen the circumferences' sigma where "
       "the parts disagree beyond theirs (0: off; at least 2)",
       &O::consistency_parts},
      {"gnss_speed_sigma_mps", "m/s", -1.0, 100.0,
       "white noise per fix of gnss.csv's speed_mps (Doppler), fitted against the wheels' "
       "distance per keyframe interval; 0: not used; negative: 0.05 where the log has the column, "
       "except with tyre_model: extended",
       &O::gnss_speed_sigma_mps},
      {"gnss_speed_correlation_s", "s", 0.0, 100.0,
       "Doppler errors of fixes closer than this are taken as one (the receiver's filter)",
       &O::gnss_speed_correlation_s},
      {"use_heading", "", 0, 0, "heading.csv residuals", &O::use_heading},
      {"use_gyro", "", 0, 0, "imu.csv yaw-rate residuals", &O::use_gyro},
      {"estimate_track_width", "", 0, 0, "also estimate the rear track width",
       &O::estimate_track_width},
      {"track_width_uncertainty", "1", 0.0, 1.0,
       "where the plain model holds the track width: how far the track the wheels roll on may "
       "lie from vehicle.yaml's (load moves it), as a share of it; its spread goes into the "
       "circumferences' sigma (0: exact)",
       &O::track_width_uncertainty},
      {"estimate_gyro_bias", "", 0, 0, "also estimate a constant gyro bias",
       &O::estimate_gyro_bias},
      {"estimate_heading_bias", "", 0, 0, "also estimate a constant heading.csv bias",
       &O::estimate_heading_bias},
      {"estimate_lever_arm", "", 0, 0, "also estimate the GNSS antenna's lever arm",
       &O::estimate_lever_arm},
      {"estimate_latency", "", 0, 0, "also estimate the GNSS latency", &O::estimate_latency},
      {"lever_arm_x_m", "m", -10.0, 10.0,
       "the GNSS antenna's position ahead of the rear axle's centre: held there, or where "
       "estimate_lever_arm starts",
       &O::lever_arm_x_m},
      {"lever_arm_y_m", "m", -10.0, 10.0,
       "the GNSS antenna's position left of the rear axle's centre: held there, or where "
       "estimate_lever_arm starts",
       &O::lever_arm_y_m},
      {"latency_s", "s", -1.0, 1.0,
       "the GNSS fixes' latency behind the wheels (a fix stamped t reports the position at t "
       "minus it): held there, or where estimate_latency starts",
       &O::latency_s},
      {"detect_mounting", "", 0, 0,
       "where the lever arm or the heading bias is not estimated and the residuals show it, "
       "calibrate again with it estimated and take that fit where it is significant",
       &O::detect_mounting},
      {"detect_latency", "", 0, 0,
       "where the latency is not estimated and the residuals follow the longitudinal "
       "acceleration, calibrate again with it estimated and take that fit where it is "
       "significant",
       &O::detect_latency},
      {"gentle_max_speed_mps", "m/s", 0.0, 1e3,
       "fit the odometry only where the speed stays below this (0: no limit)",
       &O::gentle_max_speed_mps},
      {"gentle_max_longitudinal_mps2", "m/s^2", 0.0, 1e3,
       "... and the longitudinal acceleration below this in magnitude (0: no limit)",
       &O::gentle_max_longitudinal_mps2},
      {"gentle_max_lateral_mps2", "m/s^2", 0.0, 1e3,
       "... and the lateral acceleration below this in magnitude (0: no limit)",
       &O::gentle_max_lateral_mps2},
      {"tyre_model", "", 0, 0,
       "rolling circumference: plain (none), following speed, lateral and longitudinal "
       "acceleration (extended), the wheel's load and slip from vehicle.yaml's body and the "
       "accelerometer (physical), or chosen by BIC (auto)",
       enum_member<&O::tyre_model>()},
      {"reference_speed_mps", "m/s", 0.0, 100.0,
       "beside a tyre model: the steady straight speed whose effective circumference is "
       "reported and exported to ROS 2 (whose radii are constant)",
       &O::reference_speed_mps},
      {"max_solver_iterations", "1", 1.0, 1e5, "Ceres iterations per solve",
       &O::max_solver_iterations},
      {"relinearise_relative_change", "1", 1e-12, 1.0,
       "integrate the odometry again when a parameter moves by more than this fraction",
       &O::relinearise_relative_change},
      {"max_relinearisations", "1", 0.0, 100.0, "at most this many re-linearisations",
       &O::max_relinearisations},
      {"threads", "1", 0.0, 1024.0,
       "threads the passes over the wheel samples and fixes run on (pre-integrating, folding, "
       "measuring the driving states, whitening the residuals; 0: one per core); the result is "
       "the same on any number",
       &O::threads},
      {"max_sigma_circumference_m", "m", 0.0, 1.0,
       "a circumference with a larger 1-sigma counts as not identified",
       &O::max_sigma_circumference_m},
      {"max_sigma_track_width_m", "m", 0.0, 1.0, "the same for the track width",
       &O::max_sigma_track_width_m},
      {"max_sigma_gyro_bias_radps", "rad/s", 0.0, 1.0, "the same for the gyro bias",
       &O::max_sigma_gyro_bias_radps},
      {"max_sigma_heading_bias_rad", "rad", 0.0, 10.0, "the same for the heading bias",
       &O::max_sigma_heading_bias_rad},
      {"max_sigma_lever_arm_m", "m", 0.0, 100.0, "the same for the lever arm",
       &O::max_sigma_lever_arm_m},
      {"max_sigma_latency_s", "s", 0.0, 100.0, "the same for the latency", &O::max_sigma_latency_s},
      {"max_sigma_tyre_effect", "1", 0.0, 1.0,
       "a tyre coefficient whose 1-sigma moves the circumference by more than this fraction (at "
       "the log's RMS driving state) counts as not identified",
       &O::max_sigma_tyre_effect},
  }};
  return kFields;
}

std::string BatchOptions::validate() const {
  std::string problem = check_option_ranges(fields(), *this);
  if (problem.empty() && consistency_parts == 1)
    problem = "consistency_parts = 1 compares a part with nothing: expected 0 (off) or 2 to 20";
  return problem;
}

double BatchOptions::doppler_sigma_mps(bool log_has_speed) const {
  if (!log_has_speed) return 0.0;
  if (gnss_speed_sigma_mps >= 0.0) return gnss_speed_sigma_mps;
  return tyre_model == TyreModelChoice::kExtended ? 0.0 : kDefaultDopplerSigmaMps;
}

}  // namespace odocal
