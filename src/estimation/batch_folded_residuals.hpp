#pragma once
// Every GNSS fix and every heading sample inside one keyframe interval folded into a single
// residual block (docs/batch-calibration.md, "Memory and time"). A fix's whitened error, turned
// into the keyframe's frame (the norm is the same: a fix's sigma is the same along x and y), and
// a heading sample's are linear in a short vector phi of functions of the block's unknowns:
//
//   e_j = P_j phi,  phi = [R(yaw)^T (xy + bias - origin), cos yaw, sin yaw, 1,
//                          params - params_lin, count, lever, latency, yaw + heading_bias]
//
// so the interval's cost sum_j |e_j|^2 is |R phi|^2 with R the triangular factor of the stacked
// rows P_j: the same cost with one block of at most one row per column of phi in place of two
// rows per fix and one per heading sample. One block for both streams, not one each: the factor
// needs only the union of their columns (the pose's, the parameters' and the count errors' are
// common), which cuts the folded rows that Ceres holds by about two fifths. Two things are held at
// the linearisation point: the antenna's turn within the interval (the lever arm is rotated by the
// pre-integrated yaw at the parameters integrated with; a change of the parameters turns it by
// microradians) and a robust loss's weight per fix (iteratively re-weighted at every
// re-linearisation, which reaches the same estimate).

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "batch_residuals.hpp"

namespace odocal::batch {

inline constexpr int kFoldedColumns = 5 + kParams + 2 + 2 + 1 + 1;
inline constexpr int kFoldedConstantColumn = 4;
inline constexpr int kFoldedParamsColumn = 5;  // and the next kParams - 1
inline constexpr int kFoldedCountColumn = kFoldedParamsColumn + kParams;  // and the next
inline constexpr int kFoldedLeverColumn = kFoldedCountColumn + 2;         // and the next
inline constexpr int kFoldedLatencyColumn = kFoldedLeverColumn + 2;
inline constexpr int kFoldedHeadingColumn = kFoldedLatencyColumn + 1;

// An upper triangular (or trapezoidal) factor over the entries `kept` of phi, packed: row r
// holds its columns r.. only.
struct PackedFactor {
  int rows = 0;
  std::vector<std::uint8_t> kept;
  std::vector<double> values;

  // residual = factor x phi(kept)
  template <typename T, int N>
  void multiply(const Eigen::Matrix<T, N, 1>& phi, T* residual) const {
    const int columns = static_cast<int>(kept.size());
    const double* value = values.data();
    for (int r = 0; r < rows; ++r) {
      T sum(0.0);
      for (int c = r; c < columns; ++c) sum += *value++ * phi(kept[static_cast<std::size_t>(c)]);
      residual[r] = sum;
    }
  }
};

// Which entries of phi the solver can move. The others are held (a held parameter's change is
// zero, a constant lever arm or latency keeps its value): their part of each row goes into the
// constant column, so that the factor needs fewer columns, and so fewer rows.
template <int Columns>
struct ColumnSelection {
  std::vector<std::uint8_t> kept;  // ascending, with the constant column
  int constant_column{};
  Eigen::Matrix<double, Columns, 1> held_values = Eigen::Matrix<double, Columns, 1>::Zero();

  static ColumnSelection all() {
    ColumnSelection selection;
    for (int c = 0; c < Columns; ++c) selection.kept.push_back(static_cast<std::uint8_t>(c));
    return selection;
  }
};

// Stacks rows and reduces them to their triangular factor (QR), so that |R phi| = |A phi| for
// every phi; never more rows than columns.
template <int Columns>
class RowFold {
 public:
  using Row = Eigen::Matrix<double, 1, Columns>;

  void add(const Row& row) { rows_.push_back(row); }
  bool empty() const { return rows_.empty(); }
  PackedFactor factor(
      const ColumnSelection<Columns>& selection = ColumnSelection<Columns>::all()) const {
    const auto columns = static_cast<Eigen::Index>(selection.kept.size());
    Eigen::MatrixXd stacked(static_cast<Eigen::Index>(rows_.size()), columns);
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      const Row& row = rows_[r];
      double held = 0.0;
      for (int c = 0; c < Columns; ++c) held += row(c) * selection.held_values(c);
      for (Eigen::Index k = 0; k < columns; ++k) {
        const int c = selection.kept[static_cast<std::size_t>(k)];
        stacked(static_cast<Eigen::Index>(r), k) =
            row(c) + (c == selection.constant_column ? held : 0.0);
      }
    }
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(stacked);
    PackedFactor packed;
    packed.kept = selection.kept;
    packed.rows = static_cast<int>(std::min(stacked.rows(), columns));
    for (int r = 0; r < packed.rows; ++r)
      for (Eigen::Index c = r; c < columns; ++c) packed.values.push_back(qr.matrixQR()(r, c));
    packed.values.shrink_to_fit();
    return packed;
  }

 private:
  std::vector<Row, Eigen::aligned_allocator<Row>> rows_;
};

// The GNSS fixes and heading samples of one keyframe interval. Blocks: pose, params, lever,
// latency, bias, count, heading_bias.
struct FoldedIntervalResidual {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // the fixes are taken relative to it
  PackedFactor factor;
  // The parameters the fold was linearised at: one for every fold of a solve, so pointed to,
  // not copied (it must outlive the fold).
  const ParamsVector* params_lin = nullptr;

  // Fix j's whitened row pair (x, y) with weight `weight` (a robust loss's, 1 without one).
  static void add_fix(RowFold<kFoldedColumns>& fold, const RelativeMotion& motion,
                      const Eigen::Vector2d& velocity, const Eigen::Vector2d& measured_from_origin,
                      double sigma_m, double weight) {
    const double scale = std::sqrt(weight) / sigma_m;
    const double z_x = measured_from_origin.x(), z_y = measured_from_origin.y();
    const double c = std::cos(motion.delta(2)), s = std::sin(motion.delta(2));
    Eigen::Matrix<double, 2, kFoldedColumns> rows;
    rows.setZero();
    rows.block<2, 2>(0, 0).setIdentity();
    rows.block<2, 2>(0, 2) << -z_x, -z_y, -z_y, z_x;
    rows.col(kFoldedConstantColumn) = motion.delta.head<2>();
    rows.block<2, kParams>(0, kFoldedParamsColumn) = motion.J_delta_params.topRows<2>();
    rows.block<2, 2>(0, kFoldedCountColumn) = -motion.J_delta_first_increment.topRows<2>();
    rows.block<2, 2>(0, kFoldedLeverColumn) << c, -s, s, c;
    rows.col(kFoldedLatencyColumn) = -velocity;
    fold.add(scale * rows.row(0));
    fold.add(scale * rows.row(1));
  }

  // A heading sample's row; `measured_rad` is the sample unwrapped to within pi of its
  // prediction.
  static void add_heading(RowFold<kFoldedColumns>& fold, const RelativeMotion& motion,
                          double measured_rad, double sigma_rad) {
    Eigen::Matrix<double, 1, kFoldedColumns> row;
    row.setZero();
    row(kFoldedHeadingColumn) = 1.0;
    row(kFoldedConstantColumn) = motion.delta(2) - measured_rad;
    row.segment<kParams>(kFoldedParamsColumn) = motion.J_delta_params.row(2);
    row.segment<2>(kFoldedCountColumn) = -motion.J_delta_first_increment.row(2);
    fold.add(row / sigma_rad);
  }

  template <typename T>
  bool operator()(const T* pose, const T* params, const T* lever, const T* latency, const T* bias,
                  const T* count, const T* heading_bias, T* residual) const {
    using std::cos, std::sin;
    const T c = cos(pose[2]), s = sin(pose[2]);
    const T x = pose[0] + bias[0] - origin.x(), y = pose[1] + bias[1] - origin.y();
    Eigen::Matrix<T, kFoldedColumns, 1> phi;
    phi << c * x + s * y, -s * x + c * y, c, s, T(1.0), Eigen::Matrix<T, kParams, 1>::Zero(),
        count[0], count[1], lever[0], lever[1], latency[0], pose[2] + heading_bias[0];
    for (int p = 0; p < kParams; ++p) phi(kFoldedParamsColumn + p) = params[p] - (*params_lin)(p);
    factor.multiply(phi, residual);
    return true;
  }
};

}  // namespace odocal::batch
