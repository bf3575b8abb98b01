#pragma once
// Backends working on one Problem (private to the fit module). Each updates problem.natural()
// for the problem's current free set and says how it went.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "fitlib/fit/problem.hpp"

namespace fitlib::fit::detail {

struct StageOutcome {
  bool converged = false;
  bool usable = true;  // false: the stage left the point unchanged (no usable solution)
  int iterations = 0;
  std::string note;  // one line for FitResult::messages (empty = nothing to say)
};

// Linear least squares with non-negativity for the free parameters flagged linear (the other
// free parameters are held). Rows are weighted by 1/(|data|·ln 10) (log10 residuals) or 1/|data|
// (relative), the first-order form of the exact objective. Throws NumericalError when the
// linear solve fails its check.
StageOutcome run_nnls(Problem& problem);

// The weighted design of that linear solve: columns for the free linear parameters (lower
// bounds shifted to 0, ± columns for unbounded ones), rhs b, the held parameters.
struct LinearDesign {
  Eigen::MatrixXd a;
  Eigen::VectorXd b;
  std::vector<int> column_param;
  std::vector<double> column_sign;
  std::vector<int> linear, held;
};
LinearDesign linear_design(const Problem& problem);
// Writes a column solution into problem.natural(); returns how many were clamped to their
// upper bound.
int apply_linear_solution(Problem& problem, const LinearDesign& design, const Eigen::VectorXd& x);

// Levenberg–Marquardt (dense QR, one thread) on the free parameters in fitted coordinates.
StageOutcome run_ceres(Problem& problem, int max_iterations);

// Levenberg–Marquardt on the normal equations (levenberg_marquardt.cpp): Ceres's damping (Jacobi
// scaling, the scaled diagonal clamped to [1e-6, 1e32], the same radius updates) and stopping rules
// (the options' function tolerance, here on two trials in a row; parameter tolerance 1e-10,
// gradient 1e-14); parameters on an active bound held there; one Jacobian and one JᵀJ per accepted
// step, one or two Cholesky factorisations of the n × n damped system per trial.
StageOutcome run_levenberg_marquardt(Problem& problem, int max_iterations);

// Multistart LN_BOBYQA from the current point and `starts − 1` seeded points (scaled to O(1)
// in fitted coordinates); keeps the best. Budget per start: max(4·max_iterations, 10·(n + 1))
// evaluations.
StageOutcome run_nlopt(Problem& problem, int starts, int max_iterations);

// The free set restricted to parameters that can move: log-transformed parameters sitting at 0
// (inactive terms after NNLS) are left out.
std::vector<int> movable(const Problem& problem, const std::vector<int>& candidates);

// Standard errors, 95 % intervals, identifiability and metrics at problem.natural().
void assess(const Problem& problem, FitResult& result);

}  // namespace fitlib::fit::detail
