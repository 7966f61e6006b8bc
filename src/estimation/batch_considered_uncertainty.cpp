// The circumferences' sigma from what the batch takes as known: the track width held, the body's
// numbers, the held tyre coefficients and the accelerometer's forward offset, each moved by a step
// of its uncertainty (docs/tyre-model.md, docs/batch-calibration.md).
#include "batch_body_uncertainty.hpp"
#include "batch_problem.hpp"

namespace odocal::batch {

void BatchProblem::add_considered_uncertainty() {
  body_covariance_.setZero();
  held_covariance_.setZero();
  body_responses_.clear();
  held_responses_.clear();
  forward_offset_covariance_.setZero();
  forward_offset_response_.reset();
  track_covariance_.setZero();
  // The plain model's only: the tyre models carry the load transfer, the physical terms with the
  // body's uncertainty.
  // A fitted track (estimated outright, or under its prior) has its uncertainty in the data's
  // covariance.
  const double track_sigma_m =
      param_free(2) || tyre_terms_ ? 0.0 : batch_.track_width_uncertainty * std::abs(params_[2]);
  if (!tyre_terms_ && !(track_sigma_m > 0.0)) return;
  preintegrate_all(0.0, false);
  const Unknowns solution = unknowns(Folds::kKeep);
  const VehicleBody stated = body_;
  const batch::ParamsVector at = Eigen::Map<const batch::ParamsVector>(params_.data());
  constexpr double kStep = 0.25;
  const auto respond = [&] {
    solve(1);
    const batch::ParamsVector moved =
        (Eigen::Map<const batch::ParamsVector>(params_.data()) - at) / kStep;
    set_unknowns(solution);
    return moved;
  };
  if (track_sigma_m > 0.0) {  // the plain model: nothing else to consider
    // Held, the track is no result of the fit: only what it moves is kept.
    params_[2] += kStep * track_sigma_m;
    preintegrate_all(0.0, false, Folds::kKeep);
    batch::ParamsVector moved = respond();
    moved(2) = 0.0;
    track_covariance_ = moved * moved.transpose();
    preintegrate_all(0.0, false, Folds::kKeep);
    solve();
    return;
  }
  for (int j = 0; j < TyreModel::kCoefficients; ++j) {
    if (!tyre_in_fit(j) || !tyre_held(j)) continue;
    const auto index = static_cast<std::size_t>(j);
    const CarCoefficient car = car_coefficient(j);
    // A regression term has no car's value, and a fit that wandered no word of its own.
    if (!(car.sigma > 0.0) && tyre_held_wandered_[index]) continue;
    const double sigma = held_coefficient_sigma(tyre_held_estimate_[index], tyre_held_sigma_[index],
                                                car, tyre_held_value_[index], tyre_nonnegative(j));
    if (!(sigma > 0.0)) continue;
    params_[static_cast<std::size_t>(kTyreOffset) + index] += kStep * sigma;
    const batch::ParamsVector moved = respond();
    held_covariance_ += moved * moved.transpose();
    held_responses_.push_back({j, {stated, kStep * moved, kStep}});
  }
  if (*tyre_terms_ == TyreTerms::kPhysical && !tyre_model().plain()) {
    for (const BodyUncertainty& uncertainty : kBodyUncertainties) {
      if (uncertainty.all_wheel_drive_only && stated.drivetrain != Drivetrain::kAll) {
        body_responses_.push_back({stated, batch::ParamsVector::Zero(), kStep});  // moves nothing
        continue;
      }
      body_ = stated;
      body_.*(uncertainty.member) += kStep * uncertainty.sigma(stated);
      preintegrate_all(0.0, false, Folds::kKeep);
      const batch::ParamsVector moved = respond();
      body_covariance_ += moved * moved.transpose();
      body_responses_.push_back({body_, kStep * moved, kStep});
    }
    body_ = stated;
    if (forward_offset_sigma_mps2_ > 0.0) {
      const auto shift = [&](double by) {
        for (DrivingState& state : states_)
          state.specific_force_x_mps2 = static_cast<float>(state.specific_force_x_mps2 + by);
      };
      shift(kStep * forward_offset_sigma_mps2_);
      preintegrate_all(0.0, false, Folds::kKeep);
      const batch::ParamsVector moved = respond();
      forward_offset_covariance_ = moved * moved.transpose();
      forward_offset_response_ = Response{stated, kStep * moved, kStep};
      shift(-kStep * forward_offset_sigma_mps2_);
    }
    preintegrate_all(0.0, false, Folds::kKeep);
  }
  solve();  // the solution's own problem again, for the summary (it starts converged)
}

}  // namespace odocal::batch
