#include "odocal/estimation/batch_options.hpp"

namespace odocal {

const char* robust_loss_name(RobustLoss loss) {
  switch (loss) {
    case RobustLoss::kNone:
      return "none";
    case RobustLoss::kHuber:
      return "huber";
    case RobustLoss::kCauchy:
      return "cauchy";
  }
  return "none";
}

std::string BatchOptions::validate() const {
  if (!(keyframe_interval_s > 0.0)) return "keyframe_interval_s must be positive";
  if (slip_sigma_m_per_sqrt_m < 0.0) return "slip_sigma_m_per_sqrt_m must not be negative";
  if (gnss_gauss_markov_sigma_m < 0.0 || !(gnss_gauss_markov_tau_s > 0.0))
    return "the Gauss-Markov GNSS sigma must not be negative and its tau must be positive";
  if (!(gnss_loss_scale > 0.0)) return "gnss_loss_scale must be positive";
  if (max_solver_iterations < 1) return "max_solver_iterations must be at least 1";
  if (!(relinearise_relative_change > 0.0) || max_relinearisations < 0)
    return "relinearise_relative_change must be positive, max_relinearisations not negative";
  return "";
}

}  // namespace odocal
