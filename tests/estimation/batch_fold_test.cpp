// The batch's memory-bounded pieces against independent truth: a folded block of fixes has the
// cost of the fixes it stands for (docs/batch-calibration.md, "Memory and time"), and the
// marginal covariances from the information matrix equal Ceres' own Covariance.

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "estimation/batch_covariance.hpp"
#include "estimation/batch_folded_residuals.hpp"

namespace odocal {
namespace {

using batch::kParams;

struct RandomMotion {
  std::mt19937 rng{7};
  std::normal_distribution<double> normal{0.0, 1.0};

  double draw(double sigma) { return sigma * normal(rng); }
  batch::RelativeMotion motion(const batch::ParamsVector& params_lin) {
    batch::RelativeMotion m;
    m.delta = Eigen::Vector3d(draw(10.0), draw(3.0), draw(0.5));
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < kParams; ++c) m.J_delta_params(r, c) = draw(5.0);
      for (int c = 0; c < 2; ++c) m.J_delta_first_increment(r, c) = draw(1.0);
    }
    m.params_lin = params_lin;
    return m;
  }
};

struct Unknowns {
  std::array<double, 3> pose{105.0, -42.0, 2.3};
  std::array<double, kParams> params{};
  std::array<double, 2> lever{0.8, -0.3};
  double latency = 0.04;
  std::array<double, 2> bias{0.5, -1.1};
  std::array<double, 2> count{0.002, -0.001};
  double heading_bias = 0.01;
};

batch::ParamsVector lin_params() {
  batch::ParamsVector p = batch::ParamsVector::Zero();
  p.head<3>() << 1.96, 1.97, 1.6;
  return p;
}

// The squared norm of a folded block's residual at `at`.
double folded_cost(const batch::FoldedIntervalResidual& folded, const Unknowns& at) {
  Eigen::VectorXd r(folded.factor.rows);
  folded(at.pose.data(), at.params.data(), at.lever.data(), &at.latency, at.bias.data(),
         at.count.data(), &at.heading_bias, r.data());
  return r.squaredNorm();
}

// The sum of the fixes' squared whitened residuals at `at`, each on its own.
double fixes_cost(const std::vector<batch::GnssResidual>& fixes, const Unknowns& at) {
  double sum = 0.0;
  for (const batch::GnssResidual& fix : fixes) {
    Eigen::Vector2d r;
    fix(at.pose.data(), at.params.data(), at.lever.data(), &at.latency, at.bias.data(),
        at.count.data(), r.data());
    sum += r.squaredNorm();
  }
  return sum;
}

TEST(FoldedGnss, HasTheCostOfTheFixesItFolds) {
  RandomMotion random;
  const batch::ParamsVector p_lin = lin_params();
  Unknowns u;
  Eigen::Map<batch::ParamsVector>(u.params.data()) = p_lin;
  const Eigen::Vector2d origin(100.0, -40.0);
  batch::RowFold<batch::kFoldedColumns> fold;
  std::vector<batch::GnssResidual> fixes;
  for (int j = 0; j < 7; ++j) {
    const batch::RelativeMotion motion = random.motion(p_lin);
    const Eigen::Vector2d velocity(random.draw(10.0), random.draw(1.0));
    const Eigen::Vector2d measured = origin + Eigen::Vector2d(random.draw(20.0), random.draw(20.0));
    const double sigma = 1.0 + 0.5 * j;
    fixes.push_back({motion, velocity, measured, sigma});
    batch::FoldedIntervalResidual::add_fix(fold, motion, velocity, measured - origin, sigma, 1.0);
  }
  const batch::FoldedIntervalResidual folded{origin, fold.factor(), &p_lin};
  ASSERT_EQ(folded.factor.rows, 14);  // 7 fixes: fewer rows than the 25 columns
  // At the parameters integrated with and zero count errors, exact (the lever arm turns with
  // the integrated yaw)...
  u.count = {0.0, 0.0};
  const double per_fix = fixes_cost(fixes, u);
  EXPECT_NEAR(folded_cost(folded, u), per_fix, 1e-9 * per_fix);
  // ... and anywhere without a lever arm.
  u.lever = {0.0, 0.0};
  u.count = {0.002, -0.001};
  u.params[0] += 0.01;
  u.params[4] += 1e-3;
  u.pose[2] -= 1.0;
  const double per_fix_moved = fixes_cost(fixes, u);
  EXPECT_NEAR(folded_cost(folded, u), per_fix_moved, 1e-9 * per_fix_moved);
}

TEST(FoldedGnss, HeldEntriesGoIntoTheConstantColumn) {
  RandomMotion random;
  const batch::ParamsVector p_lin = lin_params();
  batch::RowFold<batch::kFoldedColumns> fold;
  for (int j = 0; j < 9; ++j) {
    batch::FoldedIntervalResidual::add_fix(
        fold, random.motion(p_lin), Eigen::Vector2d(random.draw(10.0), random.draw(1.0)),
        Eigen::Vector2d(random.draw(20.0), random.draw(20.0)), 2.0, 1.0);
  }
  Unknowns u;
  Eigen::Map<batch::ParamsVector>(u.params.data()) = p_lin;
  // Free: c_RL, c_RR, count errors; held: the rest, the lever arm and latency at their values.
  batch::ColumnSelection<batch::kFoldedColumns> selection;
  selection.constant_column = 4;
  selection.kept = {0, 1, 2, 3, 4, 5, 6, 5 + kParams, 6 + kParams};
  selection.held_values(7 + kParams) = u.lever[0];
  selection.held_values(8 + kParams) = u.lever[1];
  selection.held_values(9 + kParams) = u.latency;
  const batch::FoldedIntervalResidual full{Eigen::Vector2d::Zero(), fold.factor(), &p_lin};
  const batch::FoldedIntervalResidual reduced{Eigen::Vector2d::Zero(), fold.factor(selection),
                                              &p_lin};
  EXPECT_EQ(reduced.factor.rows, 9);  // from 18: nine fixes' rows
  u.params[0] += 0.004;
  u.params[1] -= 0.002;
  u.pose = {3.0, -4.0, 0.7};
  EXPECT_NEAR(folded_cost(reduced, u), folded_cost(full, u), 1e-9 * folded_cost(full, u));
}

TEST(FoldedGnss, AWeightScalesAFixsCost) {
  RandomMotion random;
  const batch::ParamsVector p_lin = lin_params();
  const batch::RelativeMotion motion = random.motion(p_lin);
  const Eigen::Vector2d velocity(3.0, 0.0), measured(4.0, -2.0);
  batch::RowFold<batch::kFoldedColumns> whole, quarter;
  batch::FoldedIntervalResidual::add_fix(whole, motion, velocity, measured, 2.0, 1.0);
  batch::FoldedIntervalResidual::add_fix(quarter, motion, velocity, measured, 2.0, 0.25);
  const batch::FoldedIntervalResidual a{Eigen::Vector2d::Zero(), whole.factor(), &p_lin};
  const batch::FoldedIntervalResidual b{Eigen::Vector2d::Zero(), quarter.factor(), &p_lin};
  Unknowns u;
  Eigen::Map<batch::ParamsVector>(u.params.data()) = p_lin;
  EXPECT_NEAR(folded_cost(b, u), 0.25 * folded_cost(a, u), 1e-12 * folded_cost(a, u));
}

TEST(FoldedInterval, HasTheCostOfTheFixesAndHeadingSamplesItFolds) {
  RandomMotion random;
  const batch::ParamsVector p_lin = lin_params();
  Unknowns u;
  Eigen::Map<batch::ParamsVector>(u.params.data()) = p_lin;
  u.lever = {0.0, 0.0};
  const Eigen::Vector2d origin(100.0, -40.0);
  batch::RowFold<batch::kFoldedColumns> fold;
  std::vector<batch::GnssResidual> fixes;
  std::vector<batch::HeadingResidual> samples;
  for (int j = 0; j < 30; ++j) {
    const batch::RelativeMotion motion = random.motion(p_lin);
    if (j % 3 == 0) {
      const Eigen::Vector2d velocity(random.draw(10.0), random.draw(1.0));
      const Eigen::Vector2d measured =
          origin + Eigen::Vector2d(random.draw(20.0), random.draw(20.0));
      fixes.push_back({motion, velocity, measured, 1.5});
      batch::FoldedIntervalResidual::add_fix(fold, motion, velocity, measured - origin, 1.5, 1.0);
    }
    // The sample as logged (wrapped), and unwrapped to near its prediction for the fold.
    const double predicted = u.pose[2] + motion.delta(2) + u.heading_bias;
    const double unwrapped = predicted + random.draw(0.05);
    const double logged = std::atan2(std::sin(unwrapped), std::cos(unwrapped));
    samples.push_back({motion, logged, 0.02});
    batch::FoldedIntervalResidual::add_heading(fold, motion, unwrapped, 0.02);
  }
  const batch::FoldedIntervalResidual folded{origin, fold.factor(), &p_lin};
  // One row per column: 20 rows of fixes and 30 of heading samples share the pose's, the
  // parameters' and the count errors' columns.
  ASSERT_EQ(folded.factor.rows, batch::kFoldedColumns);
  const auto per_measurement = [&](const Unknowns& at) {
    double sum = fixes_cost(fixes, at);
    for (const batch::HeadingResidual& sample : samples) {
      double r = 0.0;
      sample(at.pose.data(), at.params.data(), &at.heading_bias, at.count.data(), &r);
      sum += r * r;
    }
    return sum;
  };
  EXPECT_NEAR(folded_cost(folded, u), per_measurement(u), 1e-8 * per_measurement(u));
  u.params[1] += 0.003;
  u.count = {0.002, -0.001};
  u.heading_bias = -0.02;
  u.pose[2] += 0.1;
  EXPECT_NEAR(folded_cost(folded, u), per_measurement(u), 1e-8 * per_measurement(u));
}

// r = A [a; b; c; x] - y: a small linear problem with every kind of block.
struct LinearResidual {
  Eigen::Matrix<double, 3, 8> A;
  Eigen::Vector3d y;
  template <typename T>
  bool operator()(const T* a, const T* b, const T* c, const T* x, T* r) const {
    Eigen::Matrix<T, 8, 1> v;
    v << a[0], a[1], b[0], b[1], b[2], c[0], x[0], x[1];
    Eigen::Map<Eigen::Matrix<T, 3, 1>> out(r);
    out = A.cast<T>() * v - y.cast<T>();
    return true;
  }
};

struct SmallProblem {
  std::array<double, 2> a{0.1, 0.2};
  std::array<double, 3> b{1.0, 2.0, 3.0};
  double c = 0.5;
  std::vector<std::array<double, 2>> x = std::vector<std::array<double, 2>>(12);
  ceres::Problem problem;

  explicit SmallProblem(bool singular) {
    std::mt19937 rng(3);
    std::normal_distribution<double> normal;
    for (std::size_t i = 0; i < x.size(); ++i) {
      auto* residual = new LinearResidual;
      for (int r = 0; r < 3; ++r)
        for (int k = 0; k < 8; ++k) residual->A(r, k) = normal(rng);
      // Singular: a[0] and a[1] enter only as their sum.
      if (singular) residual->A.col(1) = residual->A.col(0);
      residual->y = Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<LinearResidual, 3, 2, 3, 1, 2>(residual), nullptr,
          a.data(), b.data(), &c, x[i].data());
    }
    problem.SetParameterBlockConstant(&c);
    problem.SetManifold(b.data(), new ceres::SubsetManifold(3, {1}));
  }
};

TEST(MarginalCovariances, EqualCeresCovarianceWithManifoldsAndConstants) {
  SmallProblem small(false);
  const auto ours = batch::marginal_covariances(
      small.problem, {{small.a.data(), 2}, {small.b.data(), 3}, {&small.c, 1}});
  ASSERT_TRUE(ours.has_value());
  ceres::Covariance::Options options;
  options.algorithm_type = ceres::SPARSE_QR;
  ceres::Covariance covariance(options);
  ASSERT_TRUE(covariance.Compute(
      {{small.a.data(), small.a.data()}, {small.b.data(), small.b.data()}}, &small.problem));
  Eigen::Matrix<double, 2, 2, Eigen::RowMajor> a;
  Eigen::Matrix<double, 3, 3, Eigen::RowMajor> b;
  covariance.GetCovarianceBlock(small.a.data(), small.a.data(), a.data());
  covariance.GetCovarianceBlock(small.b.data(), small.b.data(), b.data());
  EXPECT_LT((Eigen::MatrixXd(a) - (*ours)[0]).norm(), 1e-9 * a.norm());
  EXPECT_LT((Eigen::MatrixXd(b) - (*ours)[1]).norm(), 1e-9 * b.norm());
  EXPECT_EQ((*ours)[1](1, 1), 0.0);  // held by the manifold
  EXPECT_EQ((*ours)[2](0, 0), 0.0);  // constant
}

TEST(MarginalCovariances, NoneWhenTheInformationIsSingular) {
  SmallProblem small(true);
  EXPECT_FALSE(batch::marginal_covariances(small.problem, {{small.a.data(), 2}}).has_value());
}

// r = A [p; x_i; x_j] - y: one link of a chain.
struct LinkResidual {
  Eigen::Matrix<double, 4, 8> A;
  Eigen::Vector4d y;
  template <typename T>
  bool operator()(const T* p, const T* xi, const T* xj, T* r) const {
    Eigen::Matrix<T, 8, 1> v;
    v << p[0], p[1], xi[0], xi[1], xi[2], xj[0], xj[1], xj[2];
    Eigen::Map<Eigen::Matrix<T, 4, 1>> out(r);
    out = A.cast<T>() * v - y.cast<T>();
    return true;
  }
};

// A chain of states, each linked to the next and to one shared parameter block, like the
// batch's keyframes. `reversed` stores state i at the far end of the array, so that the blocks'
// addresses run against the order in which the problem was built.
struct ChainProblem {
  std::array<double, 2> shared{0.3, -0.1};
  std::vector<std::array<double, 3>> storage = std::vector<std::array<double, 3>>(60);
  ceres::Problem problem;

  explicit ChainProblem(bool reversed) {
    std::mt19937 rng(5);
    std::normal_distribution<double> normal;
    const auto state = [&](std::size_t i) {
      return storage[reversed ? storage.size() - 1 - i : i].data();
    };
    for (std::size_t i = 0; i + 1 < storage.size(); ++i) {
      auto* residual = new LinkResidual;
      for (int r = 0; r < 4; ++r) {
        for (int k = 0; k < 8; ++k) residual->A(r, k) = normal(rng);
        residual->y(r) = normal(rng);
      }
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<LinkResidual, 4, 2, 3, 3>(residual),
                               nullptr, shared.data(), state(i), state(i + 1));
    }
  }
};

TEST(MarginalCovariances, DoNotDependOnWhereTheBlocksLieInMemory) {
  ChainProblem forward(false);
  ChainProblem backward(true);
  const auto a = batch::marginal_covariances(forward.problem, {{forward.shared.data(), 2}});
  const auto b = batch::marginal_covariances(backward.problem, {{backward.shared.data(), 2}});
  ASSERT_TRUE(a.has_value());
  ASSERT_TRUE(b.has_value());
  // To the last bit: the same problem must give the same pivots, whatever the heap did.
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) EXPECT_EQ((*a)[0](i, j), (*b)[0](i, j)) << i << "," << j;
}

}  // namespace
}  // namespace odocal
