#pragma once
// Wheel odometry pre-integrated between two keyframes, for the batch calibration: the relative
// pose of every wheel sample in the first keyframe's frame, its Jacobian with respect to the
// parameters [c_RL, c_RR, t_R] (so that a parameter change moves it to first order without
// integrating again), and the covariance of the whole segment's relative pose from the wheel
// noise. Eqs. 1-2 of the paper, chained.

#include <Eigen/Core>
#include <array>
#include <vector>

#include "odocal/data/fitted_wheels.hpp"
#include "odocal/data/log.hpp"
#include "odocal/model/tyre_model.hpp"

namespace odocal {

// Per-wheel arc noise: slip as a random walk in arc length (variance slip^2 * |arc|), plus the
// encoder quantisation: every cumulative count is off by an independent error of sigma q
// (revolutions; 1/sqrt(12) tick). The covariance holds the errors of the segment's inner
// samples; the two end counts are left to the caller (the batch estimates them as states
// through J_delta_first_increment and J_end_last_increment).
// Lateral noise: side slip and model error move the reference point sideways, a random walk
// across the course (variance lateral^2 * |distance|).
struct WheelNoise {
  double slip_sigma_m_per_sqrt_m = 1e-3;
  double quantisation_sigma_rev = 0.0;
  double lateral_sigma_m_per_sqrt_m = 0.0;
};

struct PreintegratedSegment {
  std::size_t first_sample{};  // wheel index of the segment's first keyframe
  std::size_t last_sample{};   // ... and of its last one
  // Index s = wheel index - first_sample, 0..last-first; delta[0] = 0.
  std::vector<Pose2> delta;
  std::vector<Eigen::Matrix3d> J_delta_params;  // d delta / d [c_RL, c_RR, t_R]
  // d delta / d [n_RL, n_RR] of the first increment: how an error in the start counts moves
  // every later sample (zero at s = 0).
  std::vector<Eigen::Matrix<double, 3, 2>> J_delta_first_increment;
  // d delta.back() / d [n_RL, n_RR] of the last increment (an error in the end counts).
  Eigen::Matrix<double, 3, 2> J_end_last_increment = Eigen::Matrix<double, 3, 2>::Zero();
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // of delta.back()
  // d delta / d tyre coefficients (tyre_model.hpp); empty without a tyre model.
  std::vector<Eigen::Matrix<double, 3, TyreModel::kCoefficients>> J_delta_tyre;
  // The factors the increment into sample s was counted with, left then right ([0] unused):
  // kept for the Doppler residual of the same interval, which would compute them again. Empty
  // without a tyre model.
  std::vector<std::array<TyreFactor, 2>> tyre_factors;
};

// The tyre model to integrate with: its coefficients, the driving state at every wheel sample of
// the stream (driving_state.hpp) and the body its physical terms need.
struct TyreConditions {
  const std::vector<DrivingState>& states;
  TyreModel model;
  VehicleBody body;
};

// Requires first_sample < last_sample < wheels.size(). With a tyre model, every increment
// carries its factors (c_i,eff / c_i) and J_delta_tyre is filled.
PreintegratedSegment preintegrate(const FittedWheels& wheels, std::size_t first_sample,
                                  std::size_t last_sample, const OdometryParams& params,
                                  const WheelNoise& noise, const TyreConditions* tyre = nullptr);

}  // namespace odocal
