#pragma once
// LDLᵀ of the segment's symmetric (part of the) tangent in two halves at once: one level of nested
// dissection (docs/segment.md §Solver, "Split LDLᵀ"). A breadth-first level set of the pattern's
// graph near its middle is a separator S (no entry couples the equations before it, A, to those after
// it, B). Each half's principal block [K_hh K_hS; K_Sh K_SS] (positive definite, as K is) is
// factorised with S last on its own thread; the trailing blocks give T_h = K_SS − K_Sh K_hh⁻¹ K_hS, so
// the separator's Schur complement is T_A + T_B − K_SS (dense, small). A solve runs each half's
// forward and back substitution at once, the separator's dense solve between. The work is the same
// whichever thread runs a half, so the bytes do not depend on the thread count.
#include <array>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>

#include "worker_pool.hpp"

namespace fitlib::segment::detail {

class SplitLdlt {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double>;

  // K's pattern (both triangles stored, symmetric): the separator and each half's order; false when
  // no level set splits it into halves of at least `kSmallestHalf` of the equations each (then use one
  // LDLᵀ).
  bool analyze(const SparseMatrix& K);
  // K's values (symmetric); false when a half's pivot is zero or the Schur complement is singular.
  bool factorize(const SparseMatrix& K, WorkerPool& pool);
  Eigen::VectorXd solve(const Eigen::VectorXd& b, WorkerPool& pool) const;
  int separator_size() const { return static_cast<int>(separator_.size()); }
  int half_size(int h) const { return halves_[h].interior; }

  static constexpr double kSmallestHalf = 0.35;

 private:
  struct Half {
    int interior = 0;                  // equations of the half; its local numbering puts S after them
    std::vector<int> global;           // local index → K's equation
    SparseMatrix M;                    // upper triangle of [K_hh K_hS; K_Sh K_SS], local numbering
    std::vector<int> source;           // per nonzero of M, its slot in K's values
    Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper, Eigen::NaturalOrdering<int>> ldlt;
    Eigen::MatrixXd trailing;          // T_h
    bool ok = false;
    mutable Eigen::VectorXd work;      // a solve's local vector
  };
  void factorize_half(const SparseMatrix& K, Half& h) const;
  void forward(const Half& h, const Eigen::VectorXd& b) const;  // work = [L_hh⁻¹ b_h; −L_Sh L_hh⁻¹ b_h]
  void backward(const Half& h, const Eigen::VectorXd& x_S, Eigen::VectorXd& x) const;

  std::vector<int> separator_;             // K's equations of S, in the halves' trailing order
  std::vector<std::array<int, 3>> k_SS_;   // S × S entries of K: (row, column, slot), both triangles
  std::array<Half, 2> halves_;
  Eigen::PartialPivLU<Eigen::MatrixXd> schur_;
};

}  // namespace fitlib::segment::detail
