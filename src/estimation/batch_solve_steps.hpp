#pragma once
// The steps of a batch calibration around its BatchProblem (batch_problem.hpp): solving it to
// convergence, with a tyre model's terms, adapting the GNSS and Doppler noise to what the
// residuals show, and summarising the solution. Internal to the batch calibration; fit_model
// (batch_calibration.cpp) runs them in order.

#include <ceres/ceres.h>

#include "batch_problem.hpp"
#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/estimation/model_adequacy.hpp"

namespace odocal::batch {

// Solves until the parameters stop moving by more than relinearise_relative_change (at most
// max_relinearisations times again) and the robust loss's weights by more than
// kWeightTolerance. Re-weighting is a majorise-minimise iteration that creeps where many fixes
// sit on the loss's slope (a model that does not fit the log): up to kMaxReweightings solves
// more reach the robust estimate the whole-problem solve would (within 0.05 mm on the realistic
// Hockenheim drive; three stopped 1.3 mm short). A round that only re-weights keeps the driving
// state: measuring it again and again from the model being fitted walks the tyre coefficients
// off (8 sigma in TyreModelBatch.RecoversKnownCoefficientsWhereThePlainModelIsBiased).
//
// With `wandered`, re-weighting also stops where it does not settle, and says so: a step no
// smaller than the one two solves before, after the last re-linearisation.
ceres::Solver::Summary solve_relinearised(BatchProblem& batch, const BatchOptions& options,
                                          BatchSummary& summary, bool* wandered = nullptr);

// A tyre model's family of terms with what this log can identify: a coefficient whose sigma
// exceeds its threshold is held at zero and the rest solved again (a drive at one speed cannot
// tell k_speed from the circumference; left free, it would carry the circumference's sigma away
// with it).
ceres::Solver::Summary solve_tyre_model(BatchProblem& batch, const BatchOptions& options,
                                        BatchSummary& summary, TyreTerms terms);

// A slip coefficient is an axle's share of the force over its slip stiffness, never below zero:
// one that a solve left below zero within its noise (what the held values or the noise that
// the residuals showed moved; comma2k19's minute put the brake slip at -0.013 +- 0.006) is held
// beside the others, where a car's value and the log's word put it, and the problem solved
// again; whether it was.
bool hold_wrong_signed_slips(BatchProblem& batch, const BatchOptions& options,
                             BatchSummary& summary, ceres::Solver::Summary& solver);

// The largest coefficient's effect at the log's RMS driving state, relative to kMaxTyreEffect's
// 3 % of circumference; the side slip's (rad) counts against kMaxSideSlipRad instead, the slip
// coefficients themselves against kMaxSlipCoefficient.
double max_tyre_effect(const BatchProblem& batch);

// Whether adapt_gnss_noise measures how much the adaptation widened the circumferences' sigma
// (two marginal covariances; a judge that only reads the residuals does without).
enum class SigmaInflation { kMeasure, kSkip };

// The GNSS error in the solution's residuals; when it differs from the configured noise (a
// correlated part, or a white level off by more than 25 %), the problem is solved again with it,
// and again with what that solution's residuals show (a fit that trusts GNSS too much hides part
// of its error in the trajectory), until the noise estimate settles. The report says by how much
// that widened the circumferences' sigma.
void adapt_gnss_noise(BatchProblem& batch, const BatchOptions& options,
                      const CalibrationOptions& common, BatchSummary& summary,
                      ceres::Solver::Summary& solver,
                      SigmaInflation inflation = SigmaInflation::kMeasure);

// The Doppler residuals' scatter (the RMS of the whitened residuals): where it is wider
// than the configured noise (a receiver noisier than gnss_speed_sigma_mps, or a slip that the
// tyre model does not follow), the problem is solved again with the noise it shows, so that the
// Doppler speed weighs what it is worth beside the positions. Never narrowed: a receiver's
// velocity errors are correlated over its filter, which one interval's residual does not show.
void adapt_doppler_noise(BatchProblem& batch, const BatchOptions& options, BatchSummary& summary,
                         ceres::Solver::Summary& solver);

// Fills the summary from the solved problem: every parameter with its sigma and verdict, and
// the termination (a circumference that is not identified makes the result unusable).
void summarise(const Log& log, const BatchOptions& b, BatchProblem& batch,
               const ceres::Solver::Summary& solver, BatchSummary& summary);

// A plain model that does not explain the log: the verdict says what would (the batch's own and
// the one judged for another method read alike).
void suggest_tyre_model(ModelAdequacy& adequacy);

}  // namespace odocal::batch
