#pragma once
// The ordering of the segment's symmetric tangent (docs/segment.md §Cost): consecutive equations
// with identical columns (a node's two equations) form a group, SuiteSparse's AMD orders the
// groups' quotient graph, and each group's equations stay together. The solver numbers its
// equations in this order once, so Eigen's SimplicialLDLT factorises in natural order.
// Fewer factor nonzeros than Eigen's own AMD on the equations (27 766 against 29 080 on the medium
// drive's tangent).
#include <vector>

#include <Eigen/SparseCore>

namespace fitlib::segment::detail {

// Equation at each position of the elimination order. `last` (optional, per equation, 0 or 1): the
// equations marked 1 come after the others, and the others' order minimises the fill with them
// (SuiteSparse's CAMD; SplitLdlt's halves with their separator).
std::vector<int> grouped_amd_order(const Eigen::SparseMatrix<double>& K, const std::vector<int>& last = {});

}  // namespace fitlib::segment::detail
