// The fast covariance forms of the filters against the general Joseph update and plain matrix
// products, on random symmetric positive definite covariances.

#include "estimation/covariance_update.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

namespace odocal {
namespace {

template <int N>
Eigen::Matrix<double, N, N> random_covariance(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::Matrix<double, N, N> A;
  for (int i = 0; i < N * N; ++i) A.data()[i] = normal(rng);
  return A * A.transpose() + 0.1 * Eigen::Matrix<double, N, N>::Identity();
}

template <int R, int C>
Eigen::Matrix<double, R, C> random_matrix(std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::Matrix<double, R, C> A;
  for (int i = 0; i < R * C; ++i) A.data()[i] = normal(rng);
  return A;
}

template <typename A, typename B>
double relative_difference(const A& a, const B& b) {
  return (a - b).norm() / b.norm();
}

TEST(CovarianceUpdate, GeneralJosephEqualsTheTextbookFormForTheOptimalGain) {
  std::mt19937 rng(1);
  const Eigen::Matrix<double, 5, 5> P = random_covariance<5>(rng);
  const Eigen::Matrix<double, 3, 5> H = random_matrix<3, 5>(rng);
  const Eigen::Matrix3d R = random_covariance<3>(rng);
  const Eigen::Matrix3d S = H * P * H.transpose() + R;
  const Eigen::Matrix<double, 5, 3> K = P * H.transpose() * S.inverse();
  const Eigen::Matrix<double, 5, 5> textbook =
      (Eigen::Matrix<double, 5, 5>::Identity() - K * H) * P;
  EXPECT_LT(relative_difference(joseph_update(P, K, H, R), textbook), 1e-12);
}

TEST(CovarianceUpdate, ThinFormEqualsTheGeneralOneForAnyGain) {
  std::mt19937 rng(2);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix<double, 8, 8> P = random_covariance<8>(rng);
    const Eigen::Matrix<double, 2, 8> H2 = random_matrix<2, 8>(rng);
    const Eigen::Matrix<double, 8, 2> K2 = random_matrix<8, 2>(rng);  // not optimal: any gain
    const Eigen::Matrix2d R2 = random_covariance<2>(rng);
    EXPECT_LT(relative_difference(joseph_update_thin(P, K2, H2, R2), joseph_update(P, K2, H2, R2)),
              1e-12);
    const Eigen::Matrix<double, 1, 8> H1 = random_matrix<1, 8>(rng);
    const Eigen::Matrix<double, 8, 1> K1 = random_matrix<8, 1>(rng);
    const Eigen::Matrix<double, 1, 1> R1(2.5);
    EXPECT_LT(relative_difference(joseph_update_thin(P, K1, H1, R1), joseph_update(P, K1, H1, R1)),
              1e-12);
  }
}

TEST(CovarianceUpdate, SelectedStatesFormEqualsTheGeneralOne) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix<double, 8, 8> P = random_covariance<8>(rng);
    for (const int first : {0, 3, 6}) {
      Eigen::Matrix<double, 2, 8> H = Eigen::Matrix<double, 2, 8>::Zero();
      H.block<2, 2>(0, first).setIdentity();
      const Eigen::Matrix<double, 8, 2> K = random_matrix<8, 2>(rng);
      const Eigen::Matrix2d R = random_covariance<2>(rng);
      EXPECT_LT(
          relative_difference(joseph_update_selected(P, K, first, R), joseph_update(P, K, H, R)),
          1e-12);
    }
    Eigen::Matrix<double, 1, 8> e4 = Eigen::Matrix<double, 1, 8>::Zero();
    e4(4) = 1.0;
    const Eigen::Matrix<double, 8, 1> K1 = random_matrix<8, 1>(rng);
    const Eigen::Matrix<double, 1, 1> R1(0.3);
    EXPECT_LT(
        relative_difference(joseph_update_selected(P, K1, 4, R1), joseph_update(P, K1, e4, R1)),
        1e-12);
  }
}

TEST(CovarianceUpdate, IdentityMeasurementFormEqualsTheGeneralOne) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d sigma = random_covariance<3>(rng);
    const Eigen::Matrix3d G = random_matrix<3, 3>(rng);
    const Eigen::Vector3d r(0.5, 1.5, 0.01);
    const Eigen::Matrix3d general =
        joseph_update<3, 3>(sigma, G, Eigen::Matrix3d::Identity(), r.asDiagonal().toDenseMatrix());
    const Eigen::Matrix3d fast = joseph_update_identity_h(sigma, G, r);
    EXPECT_LT(relative_difference(fast, general), 1e-12);
    EXPECT_EQ(fast, fast.transpose());
  }
}

TEST(CovarianceUpdate, HeadingCoupledPredictionEqualsFSigmaFTransposePlusQ) {
  std::mt19937 rng(4);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d sigma = random_covariance<3>(rng);
    const double a = normal(rng), b = normal(rng);
    Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
    F(0, 2) = a;
    F(1, 2) = b;
    const Eigen::Vector3d q(0.1, 0.2, 0.003);
    const Eigen::Matrix3d general = F * sigma * F.transpose() + q.asDiagonal().toDenseMatrix();
    EXPECT_LT(relative_difference(propagate_heading_coupled(sigma, a, b, q), general), 1e-12);
  }
}

TEST(CovarianceUpdate, CoupledBlockPredictionEqualsFPFTranspose) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Matrix<double, 8, 8> P = random_covariance<8>(rng);
    const Eigen::Matrix<double, 5, 6> E = random_matrix<5, 6>(rng);
    Eigen::Matrix<double, 8, 8> F = Eigen::Matrix<double, 8, 8>::Identity();
    F.block<5, 6>(0, 2) += E;
    const Eigen::Matrix<double, 8, 8> general = F * P * F.transpose();
    propagate_coupled_block(P, E);
    EXPECT_LT(relative_difference(P, general), 1e-12);
  }
}

TEST(CovarianceUpdate, SymmetricInverseEqualsTheInverse) {
  std::mt19937 rng(6);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Matrix3d S = random_covariance<3>(rng);
    const SymmetricInverse inverse = symmetric_inverse(S);
    EXPECT_LT(relative_difference(Eigen::Matrix3d(inverse.adjugate * inverse.inverse_det),
                                  Eigen::Matrix3d(S.inverse())),
              1e-12);
  }
}

}  // namespace
}  // namespace odocal
