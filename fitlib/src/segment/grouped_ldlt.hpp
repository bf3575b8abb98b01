#pragma once
// Sparse LDLᵀ of the segment's symmetric tangent on an ordering of its own (docs/segment.md §Cost):
// AMD on the quotient graph of the equation groups (a node's two equations share their column
// pattern), and K's upper triangle copied into that order through a slot map built once, so the
// factorisation takes it without a permuted copy of its own.
#include <vector>

#include <Eigen/SparseCholesky>

namespace fitlib::segment::detail {

class GroupedLdlt {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double>;
  // Once per pattern: the ordering, the permuted upper triangle's structure and its symbolic analysis.
  void analyze(const SparseMatrix& K);
  // K: the values on the analysed pattern (both triangles; the upper one is read).
  bool factorize(const SparseMatrix& K);
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  // Equation at each position of the elimination order.
  const std::vector<int>& order() const { return order_; }
  // Nonzeros of the factor L (its fill, for tests and docs/segment.md §Cost).
  long factor_nonzeros() const;

 private:
  std::vector<int> order_;
  SparseMatrix upper_;          // P K Pᵀ, upper triangle
  std::vector<int> from_;       // upper_'s value k is K's value from_[k]
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper, Eigen::NaturalOrdering<int>> ldlt_;
};

// Elimination order of a symmetric pattern: consecutive equations with identical columns form a
// group, AMD (SuiteSparse's) orders the groups' graph, each group's equations stay together.
std::vector<int> grouped_amd_order(const Eigen::SparseMatrix<double>& K);

}  // namespace fitlib::segment::detail
