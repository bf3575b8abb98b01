#pragma once
// Sparse LDLᵀ of the segment's symmetric tangent (docs/segment.md §Cost): AMD on the quotient graph
// of the equation groups (a node's two equations share their column pattern); K's upper triangle
// copied into that order through a slot map built once; Davis's up-looking LDLᵀ (LDL, ACM TOMS 31
// (2005) 587) whose row updates take a node's two columns in one pass where they form a pair.
#include <vector>

#include <Eigen/SparseCore>

namespace fitlib::segment::detail {

class GroupedLdlt {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double>;
  // Once per pattern: the ordering, the permuted upper triangle's structure, the elimination tree
  // and the factor's column counts.
  void analyze(const SparseMatrix& K);
  // K: the values on the analysed pattern (both triangles; the upper one is read). False on a
  // zero pivot (no pivoting: the tangent's LDLᵀ, as Eigen's SimplicialLDLT).
  bool factorize(const SparseMatrix& K);
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;
  // Equation at each position of the elimination order.
  const std::vector<int>& order() const { return order_; }
  // Nonzeros of the unit lower factor L (below its diagonal).
  long factor_nonzeros() const { return static_cast<long>(L_rows_.size()); }
  // Columns j fused with j + 1 (etree parent j + 1, column j = {j + 1} ∪ column j + 1).
  int pairs() const;

 private:
  void symbolic();
  bool numeric();

  std::vector<int> order_;
  SparseMatrix upper_;                // P K Pᵀ, upper triangle
  std::vector<int> from_;             // upper_'s value k is K's value from_[k]
  std::vector<int> parent_, L_start_; // elimination tree; column j of L at [L_start_[j], L_start_[j + 1])
  std::vector<int> L_rows_;
  std::vector<double> L_values_, D_;
  std::vector<char> pair_first_;      // column j fused with j + 1
  std::vector<int> filled_, flag_, pattern_;  // work arrays of the numeric factorisation
  std::vector<double> y_, pair_y_;
};

// Elimination order of a symmetric pattern: consecutive equations with identical columns form a
// group, AMD (SuiteSparse's) orders the groups' graph, each group's equations stay together.
std::vector<int> grouped_amd_order(const Eigen::SparseMatrix<double>& K);

}  // namespace fitlib::segment::detail
