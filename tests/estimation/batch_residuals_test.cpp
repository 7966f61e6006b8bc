// The batch calibration's residuals (derivatives against numerical ones, zero at closed-form
// solutions) and its observability verdicts on a straight drive. Fast: runs under the sanitizers.

#include "estimation/batch_residuals.hpp"

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "../support/numerical_jacobian.hpp"
#include "odocal/estimation/calibration.hpp"
#include "odocal/io/scenario_io.hpp"
#include "odocal/io/simulation_writer.hpp"
#include "odocal/sim/simulator.hpp"

namespace odocal {
namespace {
// Checks a cost function's Jacobians (automatic differentiation) against central differences,
// block by block. (Not ceres::GradientChecker: its results hold Eigen matrices allocated inside
// the Ceres library, which the sanitizer build frees with a different alignment scheme.)
void expect_correct_jacobians(const ceres::CostFunction& cost,
                              std::vector<std::vector<double>> values) {
  const int residuals = cost.num_residuals();
  std::vector<const double*> parameters;
  for (const auto& block : values) parameters.push_back(block.data());
  std::vector<std::vector<double>> jacobians;
  std::vector<double*> jacobian_pointers;
  for (const auto& block : values) {
    jacobians.emplace_back(static_cast<std::size_t>(residuals) * block.size());
    jacobian_pointers.push_back(jacobians.back().data());
  }
  std::vector<double> residual(static_cast<std::size_t>(residuals));
  ASSERT_TRUE(cost.Evaluate(parameters.data(), residual.data(), jacobian_pointers.data()));
  for (std::size_t b = 0; b < values.size(); ++b) {
    const auto block_size = static_cast<Eigen::Index>(values[b].size());
    const Eigen::VectorXd at = Eigen::Map<const Eigen::VectorXd>(values[b].data(), block_size);
    const Eigen::MatrixXd numerical = testing::numerical_jacobian(
        [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
          std::vector<double> moved(x.data(), x.data() + x.size());
          std::vector<const double*> p = parameters;
          p[b] = moved.data();
          Eigen::VectorXd r(residuals);
          EXPECT_TRUE(cost.Evaluate(p.data(), r.data(), nullptr));
          return r;
        },
        at);
    const Eigen::MatrixXd analytic =
        Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            jacobians[b].data(), residuals, block_size);
    EXPECT_LT((analytic - numerical).cwiseAbs().maxCoeff(),
              1e-6 * std::max(1.0, analytic.cwiseAbs().maxCoeff()))
        << "block " << b << "\nanalytic\n"
        << analytic << "\nnumerical\n"
        << numerical;
  }
}

batch::RelativeMotion some_motion() {
  batch::RelativeMotion motion;
  motion.delta << 12.0, 1.5, 0.3;
  motion.J_delta_params << 3.1, 3.0, -0.2, 40.0, 0.5, -2.0, 1.5, 0.7, 0.9, -0.6, 0.8, -1.1, 0.3,
      -0.4,                                                                           //
      0.4, -0.5, 0.9, -3.0, 6.0, 0.2, -0.1, -0.3, 0.25, 0.15, -0.2, 0.45, 0.6, 0.35,  //
      -0.8, 0.8, -0.1, 0.05, -2.5, 0.3, 0.02, 0.1, -0.05, 0.4, 0.07, -0.3, 0.2, -0.15;
  motion.J_delta_first_increment << 1.0, 0.9, -0.3, 0.35, -1.2, 1.25;
  motion.params_lin = batch::ParamsVector::Zero();
  motion.params_lin.head<3>() << 1.95, 1.96, 1.6;
  return motion;
}

TEST(BatchResiduals, JacobiansMatchNumericalOnes) {
  const std::vector<double> pose_a{10.0, -4.0, 2.9}, pose_b{21.0, -1.0, 3.3};
  const std::vector<double> params{1.951, 1.958, 1.62, 1e-6,   3e-4, 5e-3, 1e-3,
                                   -2e-3, 4e-4,  2e-4, 1.5e-3, 0.04, 0.02, -5e-3};
  ASSERT_EQ(params.size(), static_cast<std::size_t>(batch::kParams));
  Eigen::Matrix3d sqrt_information;
  sqrt_information << 3.0, 0.2, 0.1, 0.0, 2.5, -0.3, 0.0, 0.0, 40.0;
  expect_correct_jacobians(
      ceres::AutoDiffCostFunction<batch::OdometryResidual, 3, 3, 3, batch::kParams, 2, 2>(
          new batch::OdometryResidual{some_motion(), some_motion().J_delta_first_increment,
                                      sqrt_information}),
      {pose_a, pose_b, params, {0.002, -0.001}, {-0.003, 0.001}});
  expect_correct_jacobians(
      ceres::AutoDiffCostFunction<batch::GnssResidual, 2, 3, batch::kParams, 2, 1, 2, 2>(
          new batch::GnssResidual{some_motion(), {20.0, 3.0}, {22.0, 5.0}, 2.5}),
      {pose_a, params, {0.4, -0.2}, {0.05}, {0.7, -1.1}, {0.002, -0.001}});
  expect_correct_jacobians(
      ceres::AutoDiffCostFunction<batch::HeadingResidual, 1, 3, batch::kParams, 1, 2>(
          new batch::HeadingResidual{some_motion(), -3.0, 0.15}),
      {pose_a, params, {0.02}, {0.002, -0.001}});
  expect_correct_jacobians(ceres::AutoDiffCostFunction<batch::GyroResidual, 1, 3, 3, 1>(
                               new batch::GyroResidual{0.35, 1.0, 0.003}),
                           {pose_a, pose_b, {0.001}});
  expect_correct_jacobians(ceres::AutoDiffCostFunction<batch::GaussMarkovResidual, 2, 2, 2>(
                               new batch::GaussMarkovResidual{0.98, 0.4}),
                           {{1.0, -2.0}, {0.9, -1.7}});
}

TEST(BatchResiduals, VanishAtTheirClosedFormSolutions) {
  // Keyframe a at (10, -4) heading 90 deg; the motion moves 12 m forward, 1.5 m left, turns 0.3.
  const double pose_a[3] = {10.0, -4.0, M_PI / 2};
  const double pose_b[3] = {10.0 - 1.5, -4.0 + 12.0, M_PI / 2 + 0.3};
  const double params[batch::kParams] = {1.95, 1.96, 1.6};  // = params_lin: no change
  const double no_count_error[2] = {0.0, 0.0};
  double residual[3];
  batch::OdometryResidual{some_motion(), Eigen::Matrix<double, 3, 2>::Zero(),
                          Eigen::Matrix3d::Identity()}(pose_a, pose_b, params, no_count_error,
                                                       no_count_error, residual);
  EXPECT_NEAR(Eigen::Vector3d(residual[0], residual[1], residual[2]).norm(), 0.0, 1e-12);
  // GNSS antenna 1 m ahead of the reference point, 0.1 s latency at 10 m/s forward (keyframe
  // frame x = world y here), 0.5 m east bias.
  const double lever[2] = {1.0, 0.0}, latency[1] = {0.1}, bias[2] = {0.5, 0.0};
  const double yaw = M_PI / 2 + 0.3;
  const Eigen::Vector2d expected(10.0 - 1.5 + std::cos(yaw) + 0.5,
                                 -4.0 + 12.0 + std::sin(yaw) - 10.0 * 0.1);
  batch::GnssResidual{some_motion(), {10.0, 0.0}, expected, 1.0}(pose_a, params, lever, latency,
                                                                 bias, no_count_error, residual);
  EXPECT_NEAR(std::hypot(residual[0], residual[1]), 0.0, 1e-12);
}

// Poses a whole turn apart are the same heading: the batch's start poses come from the layer-1
// reference, whose yaw may settle a turn away from where it started (a course taken while the car
// barely moves). The gyro's turn is measured against the poses' turn modulo 2 pi, as the
// odometry's is; unwrapped, 2 pi over 0.003 rad was a residual the solver bent the turns to undo.
TEST(BatchResiduals, TheGyroTurnIsTheSameAWholeTurnAway) {
  const double pose_a[3] = {0.0, 0.0, 0.0}, bias[1] = {0.001};
  const batch::GyroResidual gyro{0.35 + 0.001 * 2.0, 2.0, 0.003};  // 0.35 rad turned in 2 s
  for (const double turns : {-2.0, -1.0, 0.0, 1.0}) {
    const double pose_b[3] = {5.0, 1.0, 0.35 + 0.01 + turns * 2.0 * M_PI};
    double residual[1];
    gyro(pose_a, pose_b, bias, residual);
    EXPECT_NEAR(residual[0], 0.01 / 0.003, 1e-9) << turns << " turns apart";
  }
}

TEST(BatchCalibration, SaysWhatAStraightDriveCannotIdentify) {
  sim::Scenario scenario =
      parse_scenario("route:\n  segments:\n    - straight: 3000\n", "straight.yaml");
  scenario.ideal = true;
  Log log = simulated_log(sim::simulate(scenario));
  log.heading.reset();
  BatchOptions options;
  options.estimate_track_width = true;
  options.estimate_heading_bias = true;
  CalibrationOptions common;
  common.min_turning_for_difference_rad = 0.0;
  const BatchSummary result = calibrate_batch(log, options, common);
  bool track_said = false, heading_said = false;
  for (const EstimatedParameter& p : result.parameters) {
    if (p.name == "track_width_m") {
      EXPECT_FALSE(p.identified);
      track_said = p.verdict.find("needs more turns") != std::string::npos;
    }
    if (p.name == "heading_bias_rad") {
      EXPECT_FALSE(p.identified);
      heading_said = p.verdict.find("no heading reference") != std::string::npos;
    }
  }
  EXPECT_TRUE(track_said) << result.identifiability;
  EXPECT_TRUE(heading_said) << result.identifiability;
  EXPECT_NE(result.identifiability.find("not identified"), std::string::npos);
}

}  // namespace
}  // namespace odocal
