#include "batch_covariance.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

namespace odocal::batch {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// A free parameter block: where its tangent coordinates start, and the ambient-from-tangent
// Jacobian of its manifold (identity without one).
struct FreeBlock {
  int offset{};
  RowMajor plus_jacobian;
};

// Every parameter block in an order that the problem's construction fixes: the requested ones
// first, then as the residual blocks (kept in insertion order) first name them. Ceres lists
// parameter blocks by address, and the factorisation's elimination order, hence its pivots and
// the last digits of every covariance, would follow the heap's layout.
std::vector<const double*> construction_order(const ceres::Problem& problem,
                                              const std::vector<RequestedBlock>& first) {
  std::vector<const double*> order;
  std::unordered_set<const double*> seen;
  const auto add = [&](const double* block) {
    if (seen.insert(block).second) order.push_back(block);
  };
  for (const RequestedBlock& block : first) add(block.values);
  std::vector<ceres::ResidualBlockId> residual_blocks;
  problem.GetResidualBlocks(&residual_blocks);
  std::vector<double*> parameters;
  for (const ceres::ResidualBlockId id : residual_blocks) {
    problem.GetParameterBlocksForResidualBlock(id, &parameters);
    for (const double* block : parameters) add(block);
  }
  std::vector<double*> all;  // blocks without residuals: undetermined, so never ordered
  problem.GetParameterBlocks(&all);
  for (const double* block : all) add(block);
  return order;
}

// Free blocks numbered in construction order, so that the requested ones' coordinates are the
// first columns of the information.
std::unordered_map<const double*, FreeBlock> free_blocks(const ceres::Problem& problem,
                                                         const std::vector<RequestedBlock>& first,
                                                         int& size) {
  std::unordered_map<const double*, FreeBlock> blocks;
  size = 0;
  for (const double* block : construction_order(problem, first)) {
    if (!problem.HasParameterBlock(block) || problem.IsParameterBlockConstant(block)) continue;
    const int ambient = problem.ParameterBlockSize(block);
    const int tangent = problem.ParameterBlockTangentSize(block);
    if (tangent == 0) continue;
    FreeBlock free{size, RowMajor::Identity(ambient, tangent)};
    if (const ceres::Manifold* manifold = problem.GetManifold(block))
      manifold->PlusJacobian(block, free.plus_jacobian.data());
    blocks.emplace(block, std::move(free));
    size += tangent;
  }
  return blocks;
}

// J^T J over every residual block, upper triangle, in tangent coordinates. Built in chunks so
// that the triplets never hold more than the information itself does.
Eigen::SparseMatrix<double> information(const ceres::Problem& problem,
                                        const std::unordered_map<const double*, FreeBlock>& blocks,
                                        int size) {
  constexpr std::size_t kMinChunk = 1 << 16;
  Eigen::SparseMatrix<double> H(size, size);
  std::vector<Eigen::Triplet<double>> triplets;
  const auto flush = [&] {
    Eigen::SparseMatrix<double> chunk(size, size);
    chunk.setFromTriplets(triplets.begin(), triplets.end());
    H += chunk;
    triplets.clear();
  };
  std::vector<ceres::ResidualBlockId> residual_blocks;
  problem.GetResidualBlocks(&residual_blocks);
  std::vector<double*> parameters;
  for (const ceres::ResidualBlockId id : residual_blocks) {
    problem.GetParameterBlocksForResidualBlock(id, &parameters);
    const ceres::CostFunction* cost = problem.GetCostFunctionForResidualBlock(id);
    const int rows = cost->num_residuals();
    std::vector<RowMajor> ambient(parameters.size());
    std::vector<double*> jacobians(parameters.size());
    for (std::size_t b = 0; b < parameters.size(); ++b) {
      ambient[b].resize(rows, problem.ParameterBlockSize(parameters[b]));
      jacobians[b] = ambient[b].data();
    }
    Eigen::VectorXd residuals(rows);
    if (!cost->Evaluate(parameters.data(), residuals.data(), jacobians.data())) continue;
    // Tangent Jacobians of the free blocks, side by side, with their columns' indices.
    std::vector<int> columns;
    std::vector<Eigen::MatrixXd> parts;
    for (std::size_t b = 0; b < parameters.size(); ++b) {
      const auto found = blocks.find(parameters[b]);
      if (found == blocks.end()) continue;
      parts.push_back(ambient[b] * found->second.plus_jacobian);
      for (int c = 0; c < parts.back().cols(); ++c) columns.push_back(found->second.offset + c);
    }
    Eigen::MatrixXd J(rows, static_cast<Eigen::Index>(columns.size()));
    Eigen::Index at = 0;
    for (const Eigen::MatrixXd& part : parts) {
      J.middleCols(at, part.cols()) = part;
      at += part.cols();
    }
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    for (Eigen::Index a = 0; a < JtJ.rows(); ++a) {
      for (Eigen::Index b = 0; b < JtJ.cols(); ++b) {
        const int i = columns[static_cast<std::size_t>(a)],
                  j = columns[static_cast<std::size_t>(b)];
        if (i <= j && JtJ(a, b) != 0.0) triplets.emplace_back(i, j, JtJ(a, b));
      }
    }
    if (triplets.size() >= std::max<std::size_t>(kMinChunk, H.nonZeros())) flush();
  }
  flush();
  return H;
}

}  // namespace

std::optional<std::vector<Eigen::MatrixXd>> marginal_covariances(
    const ceres::Problem& problem, const std::vector<RequestedBlock>& requested,
    double min_relative_pivot) {
  int size = 0;
  const auto blocks = free_blocks(problem, requested, size);
  std::vector<Eigen::MatrixXd> covariances;
  if (size == 0) {
    for (const RequestedBlock& block : requested)
      covariances.push_back(Eigen::MatrixXd::Zero(block.size, block.size));
    return covariances;
  }
  Eigen::SparseMatrix<double> H = information(problem, blocks, size);
  // Unit diagonal: the pivots then say how much of each unknown the others leave determined.
  const Eigen::VectorXd diagonal = H.diagonal();
  if (!(diagonal.array() > 0.0).all() || !diagonal.allFinite()) return std::nullopt;
  const Eigen::VectorXd scale = diagonal.cwiseSqrt().cwiseInverse();
  for (int column = 0; column < H.outerSize(); ++column) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, column); it; ++it)
      it.valueRef() *= scale(it.row()) * scale(it.col());
  }
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::AMDOrdering<int>>
      ldlt(H);
  if (ldlt.info() != Eigen::Success) return std::nullopt;
  const Eigen::VectorXd pivots = ldlt.vectorD();
  if (!pivots.allFinite() || pivots.minCoeff() < min_relative_pivot * pivots.maxCoeff())
    return std::nullopt;

  int requested_size = 0;
  for (const RequestedBlock& block : requested) {
    const auto found = blocks.find(block.values);
    if (found != blocks.end())
      requested_size += static_cast<int>(found->second.plus_jacobian.cols());
  }
  const Eigen::MatrixXd unit = Eigen::MatrixXd::Identity(size, requested_size);
  const Eigen::MatrixXd solved = ldlt.solve(unit);
  const Eigen::MatrixXd tangent = scale.head(requested_size).asDiagonal() *
                                  solved.topRows(requested_size) *
                                  scale.head(requested_size).asDiagonal();
  for (const RequestedBlock& block : requested) {
    const auto found = blocks.find(block.values);
    if (found == blocks.end()) {
      covariances.push_back(Eigen::MatrixXd::Zero(block.size, block.size));
      continue;
    }
    const RowMajor& M = found->second.plus_jacobian;
    const int offset = found->second.offset;
    covariances.push_back(M * tangent.block(offset, offset, M.cols(), M.cols()) * M.transpose());
  }
  return covariances;
}

}  // namespace odocal::batch
