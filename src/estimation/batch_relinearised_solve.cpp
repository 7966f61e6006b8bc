// Solving a batch problem to convergence: re-linearised and re-weighted until it settles, and with
// a tyre model's terms, holding what the log does not identify.
#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "batch_fit.hpp"
#include "batch_solve_steps.hpp"

namespace odocal::batch {
namespace {

// A coefficient this many sigma from zero is kept however wide its sigma: the log needs it, and
// held at zero the others would bend to stand in for it.
constexpr double kTyreSignificance = 3.0;

// A tyre model's family of terms with what this log can identify: a coefficient whose sigma
// exceeds its threshold is held at zero and the rest solved again (a drive at one speed cannot
// tell k_speed from the circumference; left free, it would carry the circumference's sigma away
// with it).
// Tyre coefficient j's variance in `uncertainty`; -1 where there is none (singular information).
double tyre_variance(const std::optional<BatchProblem::Uncertainty>& uncertainty, int j) {
  return uncertainty ? uncertainty->params(kTyreOffset + j, kTyreOffset + j) : -1.0;
}

// The free coefficients this log does not identify, each with its sigma while free: too wide
// for their effect and not significant, or a driven or braked axle's slip below zero within its
// noise (never below zero: its share of the force over its slip stiffness).
enum class Unidentified { kTooWide, kBelowZero };
std::vector<std::pair<int, double>> unidentified_coefficients(BatchProblem& batch,
                                                              const BatchOptions& options,
                                                              Unidentified which) {
  const auto uncertainty = batch.uncertainty();
  std::vector<std::pair<int, double>> unidentified;
  for (int j = 0; j < TyreModel::kCoefficients; ++j) {
    if (!batch.tyre_in_fit(j) || batch.tyre_held(j)) continue;
    const double variance = tyre_variance(uncertainty, j);
    const double sigma = variance >= 0.0 ? std::sqrt(variance) : 0.0;
    const double rms = batch.regressor_rms()(j);
    const double value = batch.params()[static_cast<std::size_t>(kTyreOffset + j)];
    const bool significant = std::abs(value) > kTyreSignificance * sigma;
    const bool found = which == Unidentified::kBelowZero
                           ? batch.tyre_nonnegative(j) && value < 0.0 && !significant
                           : !(variance >= 0.0) || !(rms > 0.0) ||
                                 (sigma * rms > options.max_sigma_tyre_effect && !significant);
    if (found) {
      unidentified.emplace_back(
          j, std::isfinite(sigma) && sigma > 0.0 ? sigma : std::numeric_limits<double>::infinity());
    }
  }
  return unidentified;
}

}  // namespace

ceres::Solver::Summary solve_relinearised(BatchProblem& batch, const BatchOptions& options,
                                          BatchSummary& summary, bool* wandered) {
  constexpr double kWeightTolerance = 0.01;
  constexpr int kMaxReweightings = 20;
  const int before = summary.solves;
  ceres::Solver::Summary solver;
  constexpr double kCoarseNoise = 1e-3;  // m per sqrt(m), slip and lateral
  bool relinearise = true;
  // Re-weighting that creeps moves on from solve to solve. One that returns to where it was two
  // solves before alternates between two solutions (a model far from the log: the physical tyre
  // terms on a skid-steer robot), and more rounds only repeat them (the Husky bag: 20 rounds of a
  // two-cycle, three times over, in one tyre_model auto).
  batch::ParamsVector last(batch.params().data()), before_last = last;
  double last_step = std::numeric_limits<double>::infinity(), step_before_last = last_step;
  if (wandered) *wandered = false;
  while (true) {
    batch.preintegrate_all(summary.solves == 0 ? kCoarseNoise : 0.0, relinearise);
    const bool reweighted = batch.max_weight_change() > kWeightTolerance;
    solver = batch.solve();
    ++summary.solves;
    const int again = summary.solves - before;
    const double step = batch.change_from(last);
    const bool alternating = !relinearise && step > options.relinearise_relative_change &&
                             batch.change_from(before_last) < 0.1 * step;
    const bool wandering = wandered && !relinearise && step > options.relinearise_relative_change &&
                           step >= 0.9 * step_before_last;
    before_last = std::exchange(last, batch::ParamsVector(batch.params().data()));
    step_before_last = std::exchange(last_step, step);
    if (wandering) *wandered = true;
    if (summary.solves == 1) continue;
    relinearise = batch.relative_change() > options.relinearise_relative_change &&
                  again <= options.max_relinearisations;
    const bool reweight = reweighted && !alternating && !wandering &&
                          again <= options.max_relinearisations + kMaxReweightings;
    if (!relinearise && !reweight) break;
  }
  return solver;
}

double max_tyre_effect(const BatchProblem& batch) {
  const TyreModel::Vector k = batch.tyre_model().coefficients();
  TyreModel::Vector effect = k.cwiseProduct(batch.regressor_rms()).cwiseAbs();
  effect(kSideSlipCoefficient) *= batch::kMaxTyreEffect / batch::kMaxSideSlipRad;
  for (const int j : {kDriveSlipCoefficient, kBrakeSlipCoefficient})
    effect(j) = std::abs(k(j)) * batch::kMaxTyreEffect / batch::kMaxSlipCoefficient;
  return effect.maxCoeff();
}

ceres::Solver::Summary solve_tyre_model(BatchProblem& batch, const BatchOptions& options,
                                        BatchSummary& summary, TyreTerms terms) {
  batch.set_tyre_terms(terms);
  // Never free: left free, the drive slip of a free-rolling axle takes up what the heading and
  // the GNSS noise make of it, and the circumferences follow (the built-in circuit, front-driven:
  // +3.3 mm at sigma 1.2 mm). Held at zero, as where the log says nothing, its spread there the
  // car's (tyre_car_prior.hpp) goes into their sigma.
  if (batch.tyre_fixed_by_car(kDriveSlipCoefficient))
    batch.hold_tyre_coefficient(kDriveSlipCoefficient, std::numeric_limits<double>::infinity());
  bool wandered = false;
  ceres::Solver::Summary solver = solve_relinearised(batch, options, summary, &wandered);
  if (wandered && solver.IsSolutionUsable()) {
    // Coefficients whose fit does not settle are not what this log identifies: all of them are
    // held at zero (the Husky bag's regression terms wandered by up to 700 times the
    // circumference at its driving state; stopped where they stood, a fit that kept one of them
    // moved the circumference 21 mm). Their sigma is the one where the fit stopped.
    const auto uncertainty = batch.uncertainty();
    for (int j = 0; j < TyreModel::kCoefficients; ++j) {
      if (!batch.tyre_in_fit(j) || batch.tyre_held(j)) continue;
      const double variance = tyre_variance(uncertainty, j);
      batch.hold_tyre_coefficient(
          j, variance > 0.0 ? std::sqrt(variance) : std::numeric_limits<double>::infinity(),
          BatchProblem::FreeValue::kWandered);
    }
    batch.restart();
    return solve_relinearised(batch, options, summary);
  }
  for (int round = 0; round < TyreModel::kCoefficients && solver.IsSolutionUsable(); ++round) {
    std::vector<std::pair<int, double>> unidentified =
        unidentified_coefficients(batch, options, Unidentified::kTooWide);
    if (unidentified.empty()) break;
    // All at once, but the side slip alone first: it turns the course, not the wheels, and an
    // unidentified side slip widens the sigma of the slip terms it is correlated with, which are
    // identified without it (on the urban drive the brake slip went with it: c_RL 7.5 mm off).
    // Held one by one otherwise, the regression terms of a skid-steer robot ran away.
    const auto side_slip = std::find_if(unidentified.begin(), unidentified.end(),
                                        [](auto& u) { return u.first == kSideSlipCoefficient; });
    if (side_slip != unidentified.end()) unidentified = {*side_slip};
    for (const auto& [j, sigma] : unidentified) batch.hold_tyre_coefficient(j, sigma);
    batch.restart();
    solver = solve_relinearised(batch, options, summary);  // without what was just held
    if (batch.free_tyre_coefficients() == 0) break;
  }
  // Held at zero while deciding, as the plain model would; then at a car's value, a better guess
  // than zero for a coefficient whose sign and size are the physics' (urban drive, seed 8: the
  // brake slip held at zero put c_RL 10 mm off, at a car's 0.0175 1.4 mm).
  if (solver.IsSolutionUsable() && batch.hold_at_car_values()) {
    batch.restart();
    solver = solve_relinearised(batch, options, summary);
  }
  hold_wrong_signed_slips(batch, options, summary, solver);
  return solver;
}

bool hold_wrong_signed_slips(BatchProblem& batch, const BatchOptions& options,
                             BatchSummary& summary, ceres::Solver::Summary& solver) {
  if (!solver.IsSolutionUsable()) return false;
  const auto wrong_signed = unidentified_coefficients(batch, options, Unidentified::kBelowZero);
  if (wrong_signed.empty()) return false;
  for (const auto& [j, sigma] : wrong_signed)
    batch.hold_tyre_coefficient(j, sigma, BatchProblem::FreeValue::kBelowZero);
  batch.hold_at_car_values();
  batch.restart();
  solver = solve_relinearised(batch, options, summary);
  return true;
}

}  // namespace odocal::batch
