#pragma once
// Does the two-wheel odometry model (paper eqs. 1-2: a constant rolling circumference per rear
// wheel) explain a log? After a batch fit, the odometry residual of every keyframe interval
// (what the poses did minus what the wheels say at the fitted parameters) is compared with the
// driving state there. A model that fits leaves white residuals that depend on nothing; a tyre
// whose rolling radius moves with load, slip or speed leaves residuals that follow lateral
// acceleration (load transfer in turns: the heading residual), longitudinal acceleration
// (drive and brake slip: the along-track residual, and the Doppler speed's where the log has one),
// speed (radius growth) or the road's grade (the drive force that climbing takes, beyond
// acceleration).
// docs/model-adequacy.md.

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace odocal {

// One keyframe interval of a fitted batch problem.
struct OdometryResidualSample {
  double t0_s{}, t1_s{};
  Eigen::Vector3d pose0, pose1;  // fitted keyframe poses [x m, y m, yaw rad]
  Eigen::Vector3d error;     // poses' relative motion minus the wheels' [along m, left m, yaw rad]
  Eigen::Vector3d whitened;  // the same, whitened by the interval's odometry covariance
  // dz/ds fitted from GNSS altitude (road_grade.hpp); NaN where the log has no altitude.
  double grade{std::numeric_limits<double>::quiet_NaN()};
  // The GNSS Doppler speed's distance over the interval minus the wheels' (m); NaN where it is
  // not in the fit. Unlike the along-track error it does not come from poses that follow the
  // wheels between fixes: it sees the slip within a second.
  double doppler_error_m{std::numeric_limits<double>::quiet_NaN()};
};

// What makes a dependence count, by default: strong (|rho|) and certain (t).
inline constexpr double kMinCorrelation = 0.3;
inline constexpr double kMinTStatistic = 5.0;

// A residual's linear dependence on one driving quantity.
struct ResidualDependence {
  std::string residual;  // "heading", "along-track" or "Doppler speed"
  std::string quantity;  // "lateral acceleration", "curvature", "longitudinal acceleration",
                         // "speed squared", "grade" (over the intervals whose grade is known)
  double correlation{};  // partial correlation over the moving intervals (model_adequacy.cpp)
  double t_statistic{};  // rho sqrt(n - 2) / sqrt(1 - rho^2)

  bool counts(double min_correlation = kMinCorrelation, double min_t = kMinTStatistic) const {
    return std::abs(correlation) >= min_correlation && t_statistic >= min_t;
  }
};

struct ModelAdequacy {
  std::size_t intervals{};   // moving keyframe intervals used
  double chi2_per_dof{};     // mean squared whitened odometry residual per component
  double autocorrelation{};  // lag-1, whitened heading residuals
  std::vector<ResidualDependence> dependences;  // every pair tested
  // false: not judged (too few moving intervals, or no fit to judge); the verdict says why, and
  // `explains` says nothing.
  bool judged{false};
  bool explains{false};
  std::string verdict;  // in words
};

// How much wider than their noise model the odometry residuals are: sqrt(chi2/dof), never below 1
// (the odometry noise is set generously: a log that fits shows 0.1-0.3, which is no evidence of a
// better fit). A fit's covariance assumes its model fits; where the residuals say otherwise every
// sigma is widened by this (docs/batch-calibration.md, "A fit that its residuals reject").
double misfit_sigma_scale(const ModelAdequacy& adequacy);

// Intervals shorter than min_distance_m are left out (standing, creeping). A dependence counts
// when |rho| >= min_correlation and its t statistic >= min_t. `tyre_terms` names the tyre model
// whose residuals these are ("physical", "extended"); empty: the plain two-wheel model's. The
// verdict names the model it judges.
ModelAdequacy assess_model_adequacy(const std::vector<OdometryResidualSample>& samples,
                                    const std::string& tyre_terms = "",
                                    double min_distance_m = 0.25,
                                    double min_correlation = kMinCorrelation,
                                    double min_t = kMinTStatistic);

}  // namespace odocal
