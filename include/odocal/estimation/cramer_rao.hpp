#pragma once
// The Cramér–Rao lower bound of the rear wheel circumferences for one log: the best accuracy any
// unbiased estimator can reach from that log's GNSS positions and headings.
//
// Model: the wheel odometry is deterministic given the unknowns
//   theta = [x0 m, y0 m, yaw0 rad, c_RL m, c_RR m]
// (start pose at the first wheel sample, rear circumferences); GNSS fixes observe the position
// and heading samples the heading, each with white Gaussian noise. The Fisher information is
// sum_j S_j^T R_j^-1 S_j, where S_j = d pose(t_j) / d theta is the sensitivity of the
// dead-reckoned trajectory at the measurement time (propagated with the odometry model's
// Jacobians along the path, linearly interpolated between wheel samples). docs/results.md
// discusses what the bound leaves out (IMU, noise correlation, model error).
//
// Encoder quantisation (quantisation_sigma_rev > 0): every cumulative count is off by an
// independent error of that sigma (1/sqrt(12) tick for a counter that floors). Such an error
// shifts two increments by +e and -e; the heading blip between them moves the rest of the
// trajectory sideways, so the dead-reckoned positions carry a random walk that GNSS cannot
// average away. The measurements' noise is then correlated: the information is summed over the
// innovations of a Kalman filter of that noise process (states: pose error, current count
// errors) run on the sensitivity columns, i.e. S^T Sigma^-1 S without forming Sigma. A
// Gauss-Markov GNSS error joins that noise state the same way.

#include <Eigen/Core>
#include <cmath>

#include "odocal/data/log.hpp"

namespace odocal {

struct CramerRaoOptions {
  double gnss_sigma_m = 3.0;  // per axis; used when the log has no per-fix sigma_m column
  double heading_sigma_rad = 0.15;
  bool use_heading = true;              // false: GNSS positions only
  double quantisation_sigma_rev = 0.0;  // per cumulative count; 0: counts exact
  // Time-correlated GNSS error, first-order Gauss-Markov per axis (0: white only); a fix's sigma
  // is then the total and the white part what remains, as in the batch calibration.
  double gnss_gauss_markov_sigma_m = 0.0;
  double gnss_gauss_markov_tau_s = 60.0;
};

struct CramerRaoBound {
  // Inverse Fisher information of theta = [x0, y0, yaw0, c_RL, c_RR].
  Eigen::Matrix<double, 5, 5> covariance = Eigen::Matrix<double, 5, 5>::Zero();
  double sigma_c_rl_m{};
  double sigma_c_rr_m{};
  std::size_t gnss_used{};
  std::size_t heading_used{};
  // Condition number of the Fisher information after scaling each unknown to unit diagonal;
  // infinite when the log carries no information on some combination of the unknowns.
  double condition_number{};
  bool informative() const { return std::isfinite(condition_number) && condition_number < 1e12; }
  // RMS of the two circumferences' sigma, the figure the accuracy tables quote.
  double rms_sigma_circumference_m() const {
    return std::sqrt(0.5 * (sigma_c_rl_m * sigma_c_rl_m + sigma_c_rr_m * sigma_c_rr_m));
  }
};

// `params` are the true parameters and `start` the true pose at the first wheel sample: the
// sensitivities are evaluated along the trajectory they produce. Measurements outside the wheel
// time span are ignored.
CramerRaoBound circumference_cramer_rao_bound(const Log& log, const OdometryParams& params,
                                              const Pose2& start,
                                              const CramerRaoOptions& options = {});

}  // namespace odocal
