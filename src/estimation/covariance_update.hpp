#pragma once
// The covariance algebra of odocal's Kalman filters: the Joseph-form update once in general form,
// and the structured forms that the per-sample loops use instead (layer 1, layer 2). Each fast
// form is exact algebra, not an approximation: tests/estimation/covariance_update_test.cpp checks
// it against the general form.

#include <Eigen/Core>

namespace odocal {

// (I - K H) P (I - K H)^T + K R K^T, symmetrised: the covariance after a Kalman update with gain
// K, valid for any gain (Joseph form).
template <int N, int M>
Eigen::Matrix<double, N, N> joseph_update(const Eigen::Matrix<double, N, N>& P,
                                          const Eigen::Matrix<double, N, M>& K,
                                          const Eigen::Matrix<double, M, N>& H,
                                          const Eigen::Matrix<double, M, M>& R) {
  const Eigen::Matrix<double, N, N> I_KH = Eigen::Matrix<double, N, N>::Identity() - K * H;
  const Eigen::Matrix<double, N, N> updated = I_KH * P * I_KH.transpose() + K * R * K.transpose();
  return 0.5 * (updated + updated.transpose());
}

// The same through the M-row H (layer 1, M = 1 or 2 of N = 8): A = P - K (H P), then
// A (I - K H)^T = A - (A H^T) K^T. A third of the cost of forming I - K H and two N x N products.
template <int N, int M>
Eigen::Matrix<double, N, N> joseph_update_thin(const Eigen::Matrix<double, N, N>& P,
                                               const Eigen::Matrix<double, N, M>& K,
                                               const Eigen::Matrix<double, M, N>& H,
                                               const Eigen::Matrix<double, M, M>& R) {
  // lazyProduct: for fixed operands of this size Eigen's default product takes its blocked GEMM
  // path, which is slower than the coefficient-based one.
  const Eigen::Matrix<double, N, N> A = P - K.lazyProduct(H.lazyProduct(P));
  const Eigen::Matrix<double, N, N> updated =
      A - A.lazyProduct(H.transpose()).lazyProduct(K.transpose()) +
      (K * R).lazyProduct(K.transpose());
  return 0.5 * (updated + updated.transpose());
}

// H selects the M consecutive states from `first` (H = [0 I 0]: layer 1's GNSS position and
// heading): H P is P's rows there, A H^T is A's columns there.
template <int N, int M>
Eigen::Matrix<double, N, N> joseph_update_selected(const Eigen::Matrix<double, N, N>& P,
                                                   const Eigen::Matrix<double, N, M>& K, int first,
                                                   const Eigen::Matrix<double, M, M>& R) {
  const Eigen::Matrix<double, N, N> A = P - K.lazyProduct(P.template middleRows<M>(first));
  const Eigen::Matrix<double, N, N> updated =
      A - A.template middleCols<M>(first).lazyProduct(K.transpose()) +
      (K * R).lazyProduct(K.transpose());
  return 0.5 * (updated + updated.transpose());
}

// H = I with a diagonal R (layer 2, eq. 7b): (I - G) sigma (I - G)^T + G R G^T evaluated on the
// upper triangle only and mirrored, symmetric by construction.
inline Eigen::Matrix3d joseph_update_identity_h(const Eigen::Matrix3d& sigma,
                                                const Eigen::Matrix3d& G,
                                                const Eigen::Vector3d& R_diagonal) {
  const Eigen::Matrix3d I_G = Eigen::Matrix3d::Identity() - G;
  const Eigen::Matrix3d I_G_sigma = I_G.lazyProduct(sigma);
  const Eigen::Matrix3d G_R = G * R_diagonal.asDiagonal();
  Eigen::Matrix3d out;
  out.triangularView<Eigen::Upper>() =
      I_G_sigma.lazyProduct(I_G.transpose()) + G_R.lazyProduct(G.transpose());
  out.triangularView<Eigen::StrictlyLower>() = out.transpose();
  return out;
}

// F sigma F^T + diag(q) for eq. 1's pose Jacobian F = I + [a, b, 0]^T e_yaw^T (only the heading
// column couples the states): sigma plus rank-two terms, a fifth of two general 3x3 products.
inline Eigen::Matrix3d propagate_heading_coupled(const Eigen::Matrix3d& sigma, double a, double b,
                                                 const Eigen::Vector3d& q) {
  const double s02 = sigma(0, 2) + a * sigma(2, 2), s12 = sigma(1, 2) + b * sigma(2, 2);
  Eigen::Matrix3d out;
  out(0, 0) = sigma(0, 0) + a * (sigma(0, 2) + s02) + q(0);
  out(1, 1) = sigma(1, 1) + b * (sigma(1, 2) + s12) + q(1);
  out(2, 2) = sigma(2, 2) + q(2);
  out(0, 1) = out(1, 0) = sigma(0, 1) + a * sigma(1, 2) + b * s02;
  out(0, 2) = out(2, 0) = s02;
  out(1, 2) = out(2, 1) = s12;
  return out;
}

// S^-1 = adjugate / det for the symmetric positive definite S = sigma + M, from its six distinct
// cofactors. S >= M has eigenvalues >= min M, so the closed form is as accurate here as a
// Cholesky solve. Kept apart so that the state update can start on the adjugate while the
// division is still in flight (the filter's speed is the latency of its step-to-step chain).
struct SymmetricInverse {
  Eigen::Matrix3d adjugate;
  double inverse_det;
};

inline SymmetricInverse symmetric_inverse(const Eigen::Matrix3d& S) {
  Eigen::Matrix3d adjugate;
  adjugate(0, 0) = S(1, 1) * S(2, 2) - S(1, 2) * S(1, 2);
  adjugate(0, 1) = S(0, 2) * S(1, 2) - S(0, 1) * S(2, 2);
  adjugate(0, 2) = S(0, 1) * S(1, 2) - S(0, 2) * S(1, 1);
  adjugate(1, 1) = S(0, 0) * S(2, 2) - S(0, 2) * S(0, 2);
  adjugate(1, 2) = S(0, 1) * S(0, 2) - S(0, 0) * S(1, 2);
  adjugate(2, 2) = S(0, 0) * S(1, 1) - S(0, 1) * S(0, 1);
  adjugate.triangularView<Eigen::StrictlyLower>() = adjugate.transpose();
  const double det = S(0, 0) * adjugate(0, 0) + S(0, 1) * adjugate(0, 1) + S(0, 2) * adjugate(0, 2);
  return {adjugate, 1.0 / det};
}

// P <- F P F^T for layer 1's transition F = I + E, where E (5 x 6) couples rows 0-4 (position,
// velocity, yaw) to columns 2-7 (velocity, yaw, biases) only: (P + E P) + (P + E P) E^T on E's
// rows and columns, a quarter of two full 8x8 products. Not symmetrised (the caller adds noise
// first).
inline void propagate_coupled_block(Eigen::Matrix<double, 8, 8>& P,
                                    const Eigen::Matrix<double, 5, 6>& E) {
  // The blocks overlap (rows and columns 2-4), hence the eval() before each write.
  P.topRows<5>() += E.lazyProduct(P.bottomRows<6>()).eval();
  P.leftCols<5>() += P.rightCols<6>().lazyProduct(E.transpose()).eval();
}

}  // namespace odocal
