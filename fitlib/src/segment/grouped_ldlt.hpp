#pragma once
// The ordering of the segment's symmetric tangent for Eigen's SimplicialLDLT (docs/segment.md
// §Cost): consecutive equations with identical columns (a node's two equations) form a group,
// SuiteSparse's AMD orders the groups' quotient graph, and each group's equations stay together.
// Fewer factor nonzeros than Eigen's own AMD on the equations (27 766 against 29 080 on the medium
// drive's tangent).
#include <vector>

#include <Eigen/SparseCore>

namespace fitlib::segment::detail {

// Equation at each position of the elimination order.
std::vector<int> grouped_amd_order(const Eigen::SparseMatrix<double>& K);

// Eigen's ordering concept (SimplicialLDLT's third template argument): perm maps a position of the
// elimination order to its equation, as Eigen's AMDOrdering does.
struct GroupedAmdOrdering {
  using PermutationType = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;
  template <typename MatrixType>
  void operator()(const MatrixType& A, PermutationType& perm) {
    const std::vector<int> order = grouped_amd_order(Eigen::SparseMatrix<double>(A));
    perm.resize(static_cast<int>(order.size()));
    for (std::size_t p = 0; p < order.size(); ++p) perm.indices()(static_cast<int>(p)) = order[p];
  }
};

}  // namespace fitlib::segment::detail
