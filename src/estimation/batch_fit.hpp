#pragma once
// One batch fit of the plain model or of a tyre model's family of terms, and what tyre_model
// auto compares of it: batch_calibration.cpp fits (its steps: batch_solve_steps.hpp),
// tyre_model_selection.cpp chooses.

#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "calibration_run.hpp"
#include "odocal/estimation/batch_calibration.hpp"

namespace odocal::batch {

// A solved fit, taken before the GNSS noise adaptation (the information criteria are comparable
// only under one noise model).
struct FitFacts {
  bool usable = false;
  double bic = std::numeric_limits<double>::infinity();
  int free_tyre_coefficients = 0;
  bool wandered = false;         // its coefficients did not settle and were held at zero
  double max_tyre_effect = 0.0;  // largest change of a circumference at the log's RMS state
  std::array<double, 2> circumference{};
  std::array<double, 2> circumference_variance{std::numeric_limits<double>::infinity(),
                                               std::numeric_limits<double>::infinity()};
};

using FitDecision = std::function<bool(const FitFacts&)>;

// A GNSS noise model to solve under from the start: every fix's white sigma scaled, and a
// Gauss-Markov error (sigma 0: none).
struct GnssNoiseModel {
  double white_scale = 1.0;
  double gauss_markov_sigma_m = 0.0;
  double gauss_markov_tau_s = 60.0;
};

// The noise the plain fit's adaptation settled on, when it adapted (and kept) one.
std::optional<GnssNoiseModel> adapted_noise(const GnssNoiseReport& report);

// Tyre coefficients that change the circumference by more than this at the log's typical driving
// state (RMS of each regressor) are not a tyre: they are the model explaining something else.
inline constexpr double kMaxTyreEffect = 0.03;
// Nor is a side slip of more than this at the log's RMS lateral acceleration: a rear axle past
// 6 degrees of slip angle is sliding (a car's rear tyres reach ~0.03 rad at 5 m/s^2).
inline constexpr double kMaxSideSlipRad = 0.1;
// Nor a slip coefficient beyond a tyre's, judged as itself and not by its effect: k_drive_slip
// and k_brake_slip are the axle's share of the force over the slip stiffness per unit load, 10
// to 30 for road tyres (tyre_car_prior.hpp takes 20). Their effect at the RMS state is the
// tyre's slip, percents on a circuit driven to the grip: a tyre of 14 on Hockenheim slips 3.4 %
// RMS while driving.
inline constexpr double kMaxSlipCoefficient = 0.1;

// A fit after its GNSS noise adaptation: its circumferences, and the least variance it can
// report for them (the data's own, scaled as the adaptation scales it: the considered
// uncertainty, the models' spread and the misfit only add to it; infinite where the adaptation
// leaves no sigma). None where the information is singular.
struct AdaptedFacts {
  std::array<double, 2> circumference{};
  std::optional<std::array<double, 2>> min_variance;
};
using AdaptedDecision = std::function<bool(const AdaptedFacts&)>;

// What steers one fit besides its model, each optional.
struct FitControls {
  // Declines the solved fit (before its GNSS noise adaptation): then nothing more is done.
  FitDecision finish{};
  // Another tyre model's fit of the log: the circumferences' gap to it is added to their
  // variance (BatchSummary::model_spread_m).
  std::optional<std::array<double, 2>> rival_circumference{};
  // The share of that gap carried: all of it, or less where the rival fits the log only about as
  // well (tie_gap_share).
  double rival_share = 1.0;
  // A gap found before between two fits of one track, carried as found in place of the rival's
  // (a tie's, where the plain model's track is put under its prior: track_prior_fit.cpp).
  std::optional<std::array<double, 2>> carried_spread_m{};
  // A GNSS noise model to solve under from the start.
  std::optional<GnssNoiseModel> noise{};
  // Declines the adapted fit: then the summary is not filled.
  AdaptedDecision go_on{};
  // The plain model's track under its prior, in place of its share
  // (BatchProblem::set_track_prior).
  bool track_prior = false;
};

// Fits one model (the plain one, or a tyre model's family of terms); unless `controls` declines
// it, adapts its GNSS noise and fills the summary. Returns whether it did. The problem is freed
// on return.
bool fit_model(const CalibrationRun& run, const BatchOptions& options,
               const CalibrationOptions& common, std::optional<TyreTerms> terms,
               BatchSummary& summary, const FitControls& controls = {});

// The tyre models that auto tries and that judge a plain fit, in order: the physical terms
// (three coefficients of load and slip), then the regression terms (seven).
inline constexpr std::array<TyreTerms, 2> kTyreCandidates{TyreTerms::kPhysical,
                                                          TyreTerms::kRegression};

// What a model's solved fit says (FitFacts), solved under `noise` from the start (none: the
// configured one; the fit itself is discarded); its solves are added to `solves`.
FitFacts solved_facts(const CalibrationRun& run, const BatchOptions& options,
                      const CalibrationOptions& common, const BatchSummary& unfitted,
                      std::optional<TyreTerms> terms, const std::optional<GnssNoiseModel>& noise,
                      int& solves);

// Its information criterion alone.
inline double criterion_under(const CalibrationRun& run, const BatchOptions& options,
                              const CalibrationOptions& common, const BatchSummary& unfitted,
                              std::optional<TyreTerms> terms,
                              const std::optional<GnssNoiseModel>& noise, int& solves) {
  return solved_facts(run, options, common, unfitted, terms, noise, solves).bic;
}

// Coefficients that change the circumference by percents at the log's typical driving state are
// not a tyre: they are the model explaining something else (a skid-steer robot, a wrong input),
// and so is a circumference that leaves the plausible band.
bool is_tyre(const FitFacts& facts, const OdometryParams& nominal, double max_change);

// The facts a tyre model is judged by: its own fit's (under the configured GNSS noise), or,
// where that fit wandered (its coefficients held at zero) while its fit under the noise the
// plain fit's residuals showed (`shared`) can stand, that one's. Under a configured noise that
// the residuals show wrong, the coefficients can wander on the GNSS error (the realistic urban
// drive, rear-driven, a 0.5 m error over 10 s configured as 0.1 m white, the track free: the
// circumferences at rest 1.4 mm from the plain ones; under the noise shown 10.4 mm, the truth
// 12.7 mm away). A fit that settled says what the log says under its noise, and stands as it is:
// coefficients held as unidentified under a configured noise far above the receiver's (comma2k19:
// 3 m configured, 0.07 m shown), or a fit that is no tyre because the body in vehicle.yaml is
// wrong (which the noise shown, widened by the misfit, would make look like one).
const FitFacts& facts_to_judge_by(const FitFacts& own, const std::optional<FitFacts>& shared,
                                  const OdometryParams& nominal, double max_change);

// A criterion lower by this much is decisive (a Bayes factor above e^5 ~ 150: Kass and
// Raftery's "very strong" evidence), not a tie of fits that held every coefficient at zero.
inline constexpr double kDecisiveBic = 10.0;

// Where no tyre model stands: the candidate that fits the log decisively better than the plain
// model's `plain_bic` but cannot stand, the lowest criterion first (none: no such one, or a
// candidate that can stand fits the log better, which judges the plain fit or confirms it). The
// plain model does not explain such a log, and its circumferences are the ones the drive rolled
// on. Two kinds cannot stand: no tyre (a car whose tyres slip far more than a road tyre's, a slip
// stiffness of 8 per unit load, on the realistic circuit with a lower, heavier body than
// vehicle.yaml's: the plain fit 68 mm off at a sigma of 6.5 mm; the physical terms, slip
// coefficient 0.14, +25 mm at 16 mm), and a tyre whose every coefficient is held (comma2k19's
// minute with vehicle.yaml's rear roll share 0.1: the physical terms, every coefficient held at a
// car's value, fit it better by 42 and put the circumferences at rest 1.0 mm from the plain
// fit's, whose sigma was 0.14 mm).
std::optional<std::size_t> decisive_fit_that_cannot_stand(
    const std::vector<TyreCandidate>& candidates, double plain_bic);

// Where no tyre model stands and none fits the log decisively better: the tyre that the log does
// not decisively reject, its criterion less than kDecisiveBic above the plain model's (none: no
// such one). The plain fit is then not surely the better account of the log, and the plain
// circumferences carry their gap to its circumferences at rest as far as the criteria weigh it
// (tie_gap_share). The realistic urban drive, front-driven, seed 1: the plain fit, the track
// width free, beat the physical terms by 1.5 and stood 5.6 mm off at a sigma of 0.89 mm, the
// physical terms 1.2 mm off at 2.1 mm.
std::optional<std::size_t> tyre_fit_not_rejected(const std::vector<TyreCandidate>& candidates,
                                                 double plain_bic);

// A rival whose criterion is `excess` above the plain model's has the weight w = 1 / (1 +
// e^(excess / 2)) of the two (the criteria as log evidence), and a mixture of the two fits
// spreads by sqrt(w (1 - w)) times their gap: the share carried. 1 where the rival fits better
// (excess below 0): the plain fit then carries all of it.
double tie_gap_share(double excess);

// How the judging candidate fits the log against `plain_bic`, as the reports say it after "fits
// the log": "better", "decisively better (no tyre)", "about as well (BIC within 10)".
std::string how_it_fits(const TyreCandidate& candidate, double plain_bic);

// Why a candidate cannot stand, and what to check, as the verdicts say it after "it" (empty where
// it can stand).
std::string why_it_cannot_stand(const TyreCandidate& candidate);

// tyre_model auto (tyre_model_selection.cpp). Returns whether it has scored the result
// (run.finish) itself.
bool fit_auto(CalibrationRun& run, const BatchOptions& options, const CalibrationOptions& common,
              BatchSummary& summary);

// Where the physical terms stand (under auto, or chosen by hand and judge_model_adequacy on),
// the regression terms fitted beside them as their
// witness (tyre_model_witness.cpp): the physical terms rest on vehicle.yaml's body, and a body
// number stated beyond the uncertainty that their sigma carries for it moves their circumferences
// at rest without a trace in that sigma (the built-in circuit, rear-driven, the centre of
// gravity stated 0.9 m high on a car of 0.55 m: +19.3 mm at a sigma of 3.4 mm; the rear roll
// share 0.9 on one of 0.45: +18.0 mm at 3.5 mm; a rear-driven car stated front-driven: -51.5 mm
// at 5.8 mm). The regression terms need no body. Where the two models' circumferences at rest
// disagree beyond kWitnessSigmas of their combined sigma (each its own), the physical fit is
// solved again with its gap to the regression terms' in its sigma, and the verdict says so.
// Not 2: on right bodies the two disagree by up to 2.3 combined sigma (the fleet's drives of
// tests/python/test_fleet_health.py). `fitting`: the options the physical fit stood with.
// Only where the physical fit's answer stands (Termination::kConverged): a refused one is no
// confident answer to guard. Returns whether it replaced the fit (the caller scores it:
// run.finish); adds its solves.
inline constexpr double kWitnessSigmas = 3.0;
bool witness_physical_fit(const CalibrationRun& run, const BatchOptions& fitting,
                          const CalibrationOptions& common, const BatchSummary& unfitted,
                          BatchSummary& summary, int& solves);

// tyre_model extended chosen by hand (judge_model_adequacy on): the physical terms' circumferences
// at rest, fitted as their own choice fits them, for the regression terms to carry their gap to
// in their sigma as under auto (tyre_model_witness.cpp). Both extrapolate to rest from the same
// drive, and the regression terms' extrapolation can fail where their sigma does not show it: a
// drive at one speed lets their speed term take the circumference's place (the 2-hour urban drive
// without a Doppler column: -18.7 mm at a sigma of 3.0 mm, the physical terms -0.3 mm). None
// where the physical fit is not usable; its solves are added to `solves`.
std::optional<std::array<double, 2>> physical_rival(const CalibrationRun& run,
                                                    const BatchOptions& options,
                                                    const CalibrationOptions& common,
                                                    const BatchSummary& unfitted, int& solves);

// tyre_model none chosen by hand: the plain fit, judged by the tyre models as auto judges it
// (judge_against_tyre_models below, tyre_model_judge.cpp). Where one is a tyre and fits the log
// better under the same GNSS noise (or, where none is, one fits it decisively better), the plain
// circumferences are the ones this drive rolled on, not the ones at rest:
// the plain fit is solved again with its gap to that model's circumferences in its sigma, and
// its model verdict says that it does not explain the log. The caller scores the result
// (run.finish).
void fit_plain_judged(const CalibrationRun& run, const BatchOptions& options,
                      const CalibrationOptions& common, BatchSummary& summary);

// Where the plain fit stands judged by the tyre models (under auto, or tyre_model none with
// judge_model_adequacy), none fits the log better (one that fits it about as well, a tie, has its
// share of the gap carried as the held fits found it: FitControls::carried_spread_m), auto did not
// doubt the track, its model explains the log, its GNSS noise was checked (adapt_gnss_noise, not
// reverted) and the held track's share is more than half of either circumference's sigma: the
// plain model fitted again with the track under a prior of track_width_uncertainty about
// vehicle.yaml's (track_prior_fit.cpp). Held, the track is moved by its whole uncertainty while
// the turns and fixes together pin it (the built-in circuit, clean: sigma 6.35x the Cramér-Rao
// bound held, 1.08x under the prior). Where the model does not explain the log, load transfer
// moves the track the wheels roll on, and a fitted track takes the turns' misfit: the share
// stays. Replaces `summary` (scored: run.finish) where its model still explains the log and the
// refit is usable, or neither is identified; returns whether it did. `summary` is already scored.
bool fit_track_under_prior(CalibrationRun& run, const BatchOptions& options,
                           const CalibrationOptions& common, const BatchSummary& unfitted,
                           BatchSummary& summary);

// The judge's held plain fit of another method's log (judge_model_adequacy), as
// fit_track_under_prior's gate reads it: whether no tyre model fits the log better than it (at
// most a tie), whether its model explains the log, its GNSS noise, the held track's share and
// the circumferences' sigma with it.
struct HeldPlainFit {
  bool at_most_a_tie{};
  bool explains{};
  GnssNoiseReport noise;
  std::array<double, 2> track_share_m{};
  std::array<double, 2> sigma_m{};
};
// What the track under its prior says of a method's held track (vehicle.yaml's, t_0): the track
// the plain fit finds (t +- sigma_t) and the share the held estimate carries. The circumferences'
// slope on the track, g (their covariance with it over its variance: the conditional slope, the
// same held or under the prior), puts a held estimate g (t_0 - t_true) off, hence
// |g| sqrt((t_0 - t)^2 + sigma_t^2) in place of |g| times the whole track_width_uncertainty.
struct JudgedTrack {
  double track_m{};
  double sigma_m{};
  std::array<double, 2> share_m{};
};
// Where `held` passes fit_track_under_prior's gate: the plain model fitted again from `unfitted`
// (its nominal is the held track) with the track under its prior and the held fit's adapted
// noise. None where the gate fails, or the refit is not usable, its circumferences' sigma is not
// known or its track not identified, its noise adaptation reverted or its model no longer
// explains the log.
std::optional<JudgedTrack> judge_track_under_prior(const CalibrationRun& run,
                                                   const BatchOptions& options,
                                                   const CalibrationOptions& common,
                                                   const BatchSummary& unfitted,
                                                   const HeldPlainFit& held);

// The tyre models fitted as the plain model's judges, as auto fits its candidates: the physical
// terms, then the regression terms only where the physical ones fit the log better but are no
// tyre. Their criteria against the plain fit's `plain_bic` (all under the noise the plain fit
// adapted to, where it adapted: `plain_noise`); where one is a tyre that fits the log better, or
// none is and one fits it decisively better (decisive_fit_that_cannot_stand), that one.
struct TyreJudgement {
  std::vector<TyreCandidate> candidates;  // in the order fitted
  double plain_bic{};                     // as compared
  std::optional<std::size_t> better;      // the candidate whose circumferences judge the plain
  const TyreCandidate* better_fit() const { return better ? &candidates[*better] : nullptr; }
  // The share of the gap to it that the plain circumferences carry (tie_gap_share).
  double gap_share() const;
  int solves() const;
};
TyreJudgement judge_against_tyre_models(const CalibrationRun& run, const BatchOptions& options,
                                        const CalibrationOptions& common,
                                        const BatchSummary& unfitted,
                                        const GnssNoiseReport& plain_noise, double plain_bic);

// The verdict, where a tyre model fits the log better or about as well (or a model that is no
// tyre fits it decisively better): `gap_m`, the share carried, from `whose` circumferences.
void say_a_tyre_model_fits_better(ModelAdequacy& adequacy, const TyreJudgement& judgement,
                                  const std::array<double, 2>& gap_m, const char* whose);

// The plain model solved again from `unfitted` with its gap to the judgement's better fit (which
// it must have) in its sigma, so that the gap enters every sigma and verdict as summarise forms
// them, and the verdict saying so: fit_auto's decisive-no-tyre step and fit_plain_judged. The
// caller scores the result (run.finish) and counts its solves.
BatchSummary fit_plain_carrying_gap(const CalibrationRun& run, const BatchOptions& options,
                                    const CalibrationOptions& common, const BatchSummary& unfitted,
                                    const TyreJudgement& judgement);

// Whether the two-wheel model explains the log, for a method that has no pose graph of its own
// (iterative, fixed-P, augmented): the plain batch fit, started at `start`, judged on its
// odometry residuals (model_adequacy.hpp), as the batch method judges its own. The verdict is
// the model's at its best fit, not the other method's estimate's: at a held estimate a few
// tenths of a per mille off, the pose graph's correlated GNSS error takes up the drift and buries
// the dependences (comma2k19: rho against a_x -0.16 held, -0.70 free). The problem is freed on
// return.
// Judged by the tyre models too (judge_against_tyre_models): where one fits the log better, the
// judgement says how far its circumferences at rest lie from `start`'s, which the method's sigma
// then carries.
struct ModelJudgement {
  ModelAdequacy adequacy;
  std::array<double, 2> gap_m{};  // zero where no tyre model fits the log better
  // Where the gap is to a model that cannot stand (decisive_fit_that_cannot_stand): why not.
  std::string gap_cannot_stand;
  // The plain fit's circumferences and their sigma under the GNSS noise its residuals showed
  // (none where it has no sigma), and whether that noise is other than the configured one. The
  // batch is at the Cramér-Rao bound, and no estimate from the same log is surer than it.
  struct PlainFit {
    std::array<double, 2> circumference_m{};
    std::array<double, 2> sigma_m{};
    bool noise_adapted = false;
  };
  std::optional<PlainFit> plain;
  // What the held track's uncertainty moves the circumferences by (track_width_uncertainty, as
  // the plain batch carries it): the other methods hold the track too.
  std::array<double, 2> track_sigma_m{};
  double track_width_uncertainty{};
  // Where the plain fit could put the track under its prior (judge_track_under_prior): what it
  // found, track_sigma_m being its share.
  std::optional<JudgedTrack> track_under_prior;
};
ModelJudgement judge_model_adequacy(const CalibrationRun& run, const OdometryParams& start,
                                    const CalibrationOptions& common);

// The report's line on that choice (empty when auto did not choose).
std::string tyre_selection_report(const BatchSummary& summary);

}  // namespace odocal::batch
