#pragma once
// Marginal covariances of a few parameter blocks of a solved Ceres problem, from its
// Gauss-Newton information J^T J (the problem has no robust loss). Ceres' own Covariance
// factors J, whose rows grow with the residuals; the information grows with the unknowns only,
// and a sparse LDLT of it (Eigen, fill-reducing ordering) costs memory linear in the keyframes.

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace odocal::batch {

struct RequestedBlock {
  const double* values;
  int size;
};

// One ambient-space covariance per requested block, in the order asked (a block that is not in
// the problem or held constant gets zeros). None when the information is singular: some free
// unknown is not determined (a pivot below `min_relative_pivot` of a unit-diagonal scaling).
std::optional<std::vector<Eigen::MatrixXd>> marginal_covariances(
    const ceres::Problem& problem, const std::vector<RequestedBlock>& blocks,
    double min_relative_pivot = 1e-12);

}  // namespace odocal::batch
