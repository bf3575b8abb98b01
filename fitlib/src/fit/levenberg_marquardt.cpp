// Levenberg–Marquardt on the normal equations (backends.hpp run_levenberg_marquardt): for small
// dense problems whose Jacobian the model gives in closed form, where Ceres's set-up, its checks
// of every evaluation and a Householder QR of the (m + n) × n augmented Jacobian per step cost more
// than the evaluations themselves (docs/decisions.md "Fixed term counts: the polish by
// Levenberg–Marquardt on the normal equations").
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "backends.hpp"
#include "fitlib/core/error.hpp"

namespace fitlib::fit::detail {

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Ceres's defaults as run_ceres sets them: a step shorter than this relative to x ends the descent,
// and so does a gradient (max norm of the projected gradient) at or below kGradientTolerance.
constexpr double kParameterTolerance = 1e-10;
constexpr double kGradientTolerance = 1e-14;
// Ceres's defaults: the initial trust radius 1e4 (μ = 1e-4), the radius within [1e-32, 1e16], the
// damping's diagonal within [1e-6, 1e32].
constexpr double kInitialDamping = 1e-4;
constexpr double kMinDamping = 1e-16, kMaxDamping = 1e32;
constexpr double kMinDiagonal = 1e-6, kMaxDiagonal = 1e32;

}  // namespace

StageOutcome run_levenberg_marquardt(Problem& problem, int max_iterations) {
  StageOutcome outcome;
  const int nf = problem.num_free(), m = problem.num_residuals();
  if (nf == 0) {
    outcome.converged = true;
    return outcome;
  }
  Eigen::VectorXd x = problem.to_x(problem.natural());
  if (!x.allFinite()) throw core::NumericalError("levenberg-marquardt: start is not finite in fitted coordinates");
  Eigen::VectorXd lo(nf), hi(nf);
  for (int k = 0; k < nf; ++k) lo[k] = problem.lower_x(k), hi[k] = problem.upper_x(k);
  x = x.cwiseMax(lo).cwiseMin(hi);

  std::vector<double> natural = problem.natural();
  RowMatrix jac(m, nf);
  Eigen::VectorXd r(m), r_trial(m);
  problem.from_x(x.data(), natural);
  if (!problem.evaluate(natural, r.data(), jac.data())) {
    outcome.usable = false;
    outcome.note = "levenberg-marquardt: no usable solution (residuals or Jacobian not finite at the start)";
    return outcome;
  }
  const double initial_cost = 0.5 * r.squaredNorm();
  double cost = initial_cost;
  Eigen::MatrixXd a(nf, nf), scaled(nf, nf), damped(nf, nf), b(nf, nf);
  Eigen::VectorXd g(nf), scale(nf), diagonal(nf), step(nf), trial(nf), rhs(nf), fixed_u(nf);
  std::vector<bool> held(nf, false);
  // Normal matrix JᵀJ, gradient Jᵀr, the Jacobi scaling and the damping's diagonal at the current point.
  const auto linearise = [&] {
    a.setZero();
    a.selfadjointView<Eigen::Lower>().rankUpdate(jac.transpose());
    a = a.selfadjointView<Eigen::Lower>();
    g.noalias() = jac.transpose() * r;
    // Ceres's Jacobi scaling: column k by 1 / (1 + ‖J_k‖), bounded where a column vanishes (a term
    // whose modulus went to 0), unlike 1 / ‖J_k‖.
    for (int k = 0; k < nf; ++k) scale[k] = 1.0 / (1.0 + std::sqrt(a(k, k)));
    scaled = scale.asDiagonal() * a * scale.asDiagonal();
    for (int k = 0; k < nf; ++k) diagonal[k] = std::clamp(scaled(k, k), kMinDiagonal, kMaxDiagonal);
  };
  // The gradient with the components that push against an active bound removed.
  const auto projected_gradient_norm = [&] {
    double norm = 0.0;
    for (int k = 0; k < nf; ++k) {
      const bool blocked = (x[k] <= lo[k] && g[k] > 0.0) || (x[k] >= hi[k] && g[k] < 0.0);
      if (!blocked) norm = std::max(norm, std::abs(g[k]));
    }
    return norm;
  };
  linearise();
  double mu = kInitialDamping, nu = 2.0;
  int iterations = 0, small_changes = 0;
  std::string why = "iteration limit reached";
  bool converged = false;
  while (iterations < max_iterations) {
    if (projected_gradient_norm() <= kGradientTolerance) {
      converged = true, why = "gradient tolerance reached";
      break;
    }
    ++iterations;
    // (C JᵀJ C + μ D) u = −C Jᵀr, h = C u: C the Jacobi scaling, D the scaled diagonal clamped to
    // [1e-6, 1e32] (Ceres's LM damping, μ the inverse of its trust radius). A parameter on a bound
    // that the step would push out of it is held there (u_k = 0); one the step carries across a
    // bound is put on it (u_k fixed) and the others solved again with it, so the step taken is the
    // damped step of the parameters left free, not a clipped one (which need not lower the model).
    for (int k = 0; k < nf; ++k) {
      held[k] = (x[k] <= lo[k] && g[k] > 0.0) || (x[k] >= hi[k] && g[k] < 0.0);
      fixed_u[k] = 0.0;
    }
    bool solved = false;
    for (int pass = 0; pass < 2; ++pass) {
      damped = scaled;
      damped.diagonal() += mu * diagonal;
      rhs = -scale.cwiseProduct(g);  // then minus the held parameters' share
      rhs.noalias() -= damped * fixed_u;
      b = damped;
      for (int k = 0; k < nf; ++k)
        if (held[k]) b.row(k).setZero(), b.col(k).setZero(), b(k, k) = 1.0, rhs[k] = fixed_u[k];
      const Eigen::LLT<Eigen::MatrixXd> llt(b);
      if (llt.info() != Eigen::Success) break;
      step = scale.cwiseProduct(llt.solve(rhs));
      solved = true;
      bool crossed = false;
      for (int k = 0; k < nf; ++k) {
        if (held[k] || (x[k] + step[k] >= lo[k] && x[k] + step[k] <= hi[k])) continue;
        held[k] = crossed = true;
        fixed_u[k] = (std::clamp(x[k] + step[k], lo[k], hi[k]) - x[k]) / scale[k];
      }
      if (!crossed) break;
    }
    if (!solved) {
      mu = std::min(mu * nu, kMaxDamping), nu *= 2.0;
      continue;
    }
    trial = (x + step).cwiseMax(lo).cwiseMin(hi);
    step = trial - x;
    if (step.norm() <= kParameterTolerance * (x.norm() + kParameterTolerance)) {
      converged = true, why = "parameter tolerance reached";
      break;
    }
    // The model's decrease: −(gᵀh + ½ hᵀ JᵀJ h) for the projected step h.
    const double predicted = -(g.dot(step) + 0.5 * step.dot(a * step));
    problem.from_x(trial.data(), natural);
    const bool finite = problem.evaluate(natural, r_trial.data(), nullptr);
    const double trial_cost = finite ? 0.5 * r_trial.squaredNorm() : std::numeric_limits<double>::infinity();
    const double fall = cost - trial_cost;
    // Ceres's function tolerance, on two trials in a row: a change of the cost below tolerance × cost
    // ends the descent (the lower point kept) only when the next trial's change is as small. One
    // small change alone ended it too early in the flat valleys of over-parameterised series (pyvisco's
    // master at 26–30 terms, known-truth data at N above the truth's term count: costs 1e-5 to 1e-3
    // above Ceres's); at a well-determined minimum the next trial costs one evaluation.
    const bool small_change = finite && std::abs(fall) <= problem.options().tolerance * cost;
    small_changes = small_change ? small_changes + 1 : 0;
    if (small_changes >= 2) {
      if (fall > 0.0) x = trial, cost = trial_cost;
      converged = true, why = "function tolerance reached";
      break;
    }
    const double rho = predicted > 0.0 ? fall / predicted : -1.0;
    if (!(fall > 0.0) || !(rho > 0.0)) {
      mu = std::min(mu * nu, kMaxDamping), nu *= 2.0;
      if (mu >= kMaxDamping) {
        why = "no step lowers the cost";
        break;
      }
      continue;
    }
    x = trial;
    cost = trial_cost;
    if (!problem.evaluate(natural, r.data(), jac.data())) {
      outcome.usable = false;
      outcome.note = "levenberg-marquardt: no usable solution (Jacobian not finite)";
      return outcome;
    }
    linearise();
    mu = std::max(mu * std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * rho - 1.0, 3)), kMinDamping);
    nu = 2.0;
  }
  problem.from_x(x.data(), problem.natural());
  outcome.iterations = iterations;
  outcome.converged = converged;
  std::ostringstream s;
  s << "levenberg-marquardt (normal equations): " << nf << " free, " << iterations << " iterations, cost "
    << initial_cost << " -> " << cost << ", " << why;
  outcome.note = s.str();
  return outcome;
}

}  // namespace fitlib::fit::detail
