#pragma once
// The critical mode of a tangent (SteppingOptions::branch_switch; docs/segment.md §Solver, "Branch
// switch"): the eigenpair of K's symmetric part nearest zero, by inverse iteration on its LDLᵀ. At
// a bifurcation point passed by the load path that eigenvalue has crossed zero and its vector is
// the direction of the branch that leaves the fundamental path (Riks 1979; Wriggers, Nonlinear
// Finite Element Methods, §7.4).
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace fitlib::segment::detail {

struct CriticalMode {
  bool found = false;        // false: the factorisation failed or the iteration did not settle
  double eigenvalue = 0.0;   // N/mm² (the tangent's units)
  Eigen::VectorXd mode;      // per free equation, unit Euclidean norm
  int iterations = 0;
  int negative = 0;          // negative eigenvalues of K_s (Sylvester: the signs of its LDLᵀ's D)
};

// Inverse iteration x ← (K_s)⁻¹x / ‖·‖ with K_s = ½(K + Kᵀ), from a fixed start (deterministic),
// until the Rayleigh quotient changes by less than `tolerance` of itself or `max_iterations`.
CriticalMode critical_mode(const Eigen::SparseMatrix<double>& K, int max_iterations = 60, double tolerance = 1e-10);

}  // namespace fitlib::segment::detail
