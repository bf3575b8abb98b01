#pragma once
// The segment's sparse linear solves (solver.cpp's Newton): LDLᵀ (whole or in two halves at once,
// split_ldlt.hpp), UMFPACK's LU, and GMRES on the unsymmetric tangent preconditioned with its
// symmetric part's LDLᵀ.
#include <algorithm>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/UmfPackSupport>
#include <unsupported/Eigen/IterativeSolvers>

#include "split_ldlt.hpp"

namespace fitlib::segment::detail {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Sparse direct solver: LDLᵀ for the symmetric tangent (every law says symmetric_tangent, no
// follower pressure; body forces are dead) on the node groups' AMD order (grouped_ldlt.hpp),
// UMFPACK's LU otherwise (Eigen's SparseLU took 80 % of the run; docs/decisions.md); the sparsity
// pattern is analysed once per run. An unsymmetric tangent is first solved by GMRES preconditioned
// with the LDLᵀ of its symmetric part (inexact Newton, SolverKnobs::krylov_iterations), the LU only
// when that does not converge (docs/segment.md §Solver, "Unsymmetric tangents").
class LinearSolver {
 public:
  // `pool` (optional): the LDLᵀ in two halves at once on its threads (split_ldlt.hpp) where the
  // pattern splits; `split` false or no pool: one LDLᵀ.
  explicit LinearSolver(bool symmetric, WorkerPool* pool = nullptr, bool split = false)
      : symmetric_(symmetric), pool_(split ? pool : nullptr) {
    lu_.umfpackControl()(UMFPACK_IRSTEP) = 0;  // no iterative refinement: Newton corrects
  }
  bool factorize(const SparseMatrix& K) {
    if (!analysed_) {  // once per run: the pattern is fixed (build_pattern)
      if (symmetric_) analyze_ldlt(K);
      else lu_.analyzePattern(K);
      analysed_ = true, ++analyses_;
    }
    if (symmetric_) return factorize_ldlt(K);
    lu_.factorize(K);
    return lu_.info() == Eigen::Success;
  }
  int analyses() const { return analyses_; }
  bool symmetric() const { return symmetric_; }
  bool split() const { return split_; }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const {
    if (symmetric_) return solve_ldlt(b);
    return lu_.solve(b);
  }
  // The unsymmetric K x = b by GMRES (restarted never) preconditioned with the LDLᵀ of ½(K + Kᵀ):
  // true when the preconditioned residual fell below `tolerance` of its start within `iterations`.
  // The symmetric part's LDLᵀ costs a fraction of the LU, and the Fritzson point's tangent is
  // nearly symmetric, so ~3 iterations do (docs/segment.md §Cost). `kept`: GMRES first runs on the
  // last factorisation (of an earlier tangent) and refactorises only when that does not converge:
  // the preconditioner changes GMRES's path, not the solution it converges to (docs/segment.md
  // §Solver, "Kept preconditioner"). `factorized`: whether this solve factorised.
  bool krylov_solve(const SparseMatrix& K, const Eigen::VectorXd& b, int iterations, double tolerance, bool kept,
                    Eigen::VectorXd& x, bool& factorized) {
    factorized = false;
    if (symmetric_ || iterations <= 0) return false;
    if (kept && preconditioned_ && gmres(K, b, iterations, tolerance, x)) return true;
    factorized = true;
    preconditioned_ = factorize_symmetric_part(K);
    const bool converged = preconditioned_ && gmres(K, b, iterations, tolerance, x);
    krylov_fallbacks_ += !converged;
    return converged;
  }
  int krylov_iterations() const { return krylov_iterations_; }
  int krylov_fallbacks() const { return krylov_fallbacks_; }

 private:
  // GMRES from x = 0 on the current preconditioner.
  bool gmres(const SparseMatrix& K, const Eigen::VectorXd& b, int iterations, double tolerance, Eigen::VectorXd& x) {
    Eigen::Index used = iterations;
    double error = tolerance;
    x.setZero(b.size());
    // Eigen's GMRES (unsupported/IterativeSolvers) called directly: its class would copy K per solve.
    const bool stopped = Eigen::internal::gmres(K, b, x, SymmetricPart{this}, used, Eigen::Index(iterations), error);
    krylov_iterations_ += static_cast<int>(used);
    return stopped && error <= tolerance && x.allFinite();
  }
  struct SymmetricPart {  // the preconditioner: Eigen's concept needs only solve()
    const LinearSolver* solver;
    Eigen::VectorXd solve(const Eigen::VectorXd& b) const { return solver->solve_ldlt(b); }
  };
  // The symmetric matrix's LDLᵀ: in two halves at once where the pattern splits, else one.
  void analyze_ldlt(const SparseMatrix& A) {
    split_ = pool_ && split_ldlt_.analyze(A);  // on one thread too: the bytes do not depend on the count
    if (!split_) ldlt_.analyzePattern(A);
  }
  bool factorize_ldlt(const SparseMatrix& A) {
    if (split_) return split_ldlt_.factorize(A, *pool_);
    ldlt_.factorize(A);
    return ldlt_.info() == Eigen::Success;
  }
  Eigen::VectorXd solve_ldlt(const Eigen::VectorXd& b) const { return split_ ? split_ldlt_.solve(b, *pool_) : ldlt_.solve(b); }
  // ½(K + Kᵀ) into sym_ (K's pattern is symmetric) and its LDLᵀ (K's numbering is the grouped AMD
  // order, StaticRun).
  bool factorize_symmetric_part(const SparseMatrix& K) {
    if (transpose_.empty()) {
      sym_ = K;
      for (int j = 0; j < K.outerSize(); ++j)
        for (SparseMatrix::InnerIterator it(K, j); it; ++it) {
          const int* column = K.innerIndexPtr() + K.outerIndexPtr()[it.row()];
          const int* end = K.innerIndexPtr() + K.outerIndexPtr()[it.row() + 1];
          transpose_.push_back(static_cast<int>(std::lower_bound(column, end, j) - K.innerIndexPtr()));
        }
      analyze_ldlt(sym_);
      ++analyses_;
    }
    const double* v = K.valuePtr();
    double* w = sym_.valuePtr();
    for (std::size_t k = 0; k < transpose_.size(); ++k) w[k] = 0.5 * (v[k] + v[transpose_[k]]);
    return factorize_ldlt(sym_);
  }

  bool symmetric_, analysed_ = false;
  WorkerPool* pool_ = nullptr;
  bool split_ = false;  // the LDLᵀ is split_ldlt_'s (analyze_ldlt)
  SplitLdlt split_ldlt_;
  bool preconditioned_ = false;  // the LDLᵀ holds a symmetric part's factorisation (krylov_solve)
  int analyses_ = 0, krylov_iterations_ = 0, krylov_fallbacks_ = 0;
  // The equations are numbered in the node groups' AMD order (ordered_pattern), so the factorisation
  // reads K's upper triangle in place (no permuted copy per factorisation).
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper, Eigen::NaturalOrdering<int>> ldlt_;
  Eigen::UmfPackLU<SparseMatrix> lu_;
  SparseMatrix sym_;            // the unsymmetric tangent's symmetric part (krylov_solve)
  std::vector<int> transpose_;  // per nonzero of K, the slot of its transposed entry
};

}  // namespace fitlib::segment::detail
