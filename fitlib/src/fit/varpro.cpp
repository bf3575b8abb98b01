#include "varpro.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "fitlib/core/error.hpp"

namespace fitlib::fit::detail {
namespace {

// Relative fall of the cost below which the projection stops; Ceres finishes from there (a few
// iterations: the tail of variable projection converges linearly).
constexpr double kGain = 1e-6;

// The linear parameters re-solved at the current non-linear ones; the cost there (+inf when the
// solve or the evaluation fails).
double project(Problem& problem, const std::vector<int>& all) {
  problem.set_free(all);
  try {
    run_nnls(problem);
  } catch (const core::NumericalError&) {
    return INFINITY;
  }
  return problem.cost(problem.natural());
}

// Kaufman's step: the Jacobian of the non-linear parameters with the span of the active linear
// columns removed (their moduli are re-solved anyway), then a damped Gauss–Newton solve.
Eigen::VectorXd lm_step(const Eigen::MatrixXd& jt, const Eigen::MatrixXd& jl, const Eigen::VectorXd& r, double mu) {
  Eigen::MatrixXd projected = jt;
  if (jl.cols() > 0) {
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(jl);
    const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(jl.rows(), qr.rank());
    projected -= q * (q.transpose() * jt);
  }
  Eigen::MatrixXd a = projected.transpose() * projected;
  const Eigen::VectorXd g = projected.transpose() * r;
  const double floor = 1e-12 * std::max(a.diagonal().maxCoeff(), 1e-300);
  for (int k = 0; k < a.rows(); ++k) a(k, k) += mu * std::max(a(k, k), floor);
  return -a.ldlt().solve(g);
}

}  // namespace

StageOutcome run_varpro(Problem& problem, int max_iterations) {
  StageOutcome out;
  const std::vector<int> all = problem.free();
  std::vector<int> nonlinear;
  for (int i : all)
    if (!problem.specs()[i].linear) nonlinear.push_back(i);
  double cost = project(problem, all);
  if (nonlinear.empty() || !std::isfinite(cost)) {
    out.usable = std::isfinite(cost);
    problem.set_free(all);
    return out;
  }
  const int m = problem.num_residuals();
  double mu = 1e-3;
  std::vector<double> best = problem.natural();
  for (; out.iterations < max_iterations; ++out.iterations) {
    // Residuals and Jacobian at the projected point, over the movable parameters.
    problem.set_free(movable(problem, all));
    const int nf = problem.num_free();
    Eigen::VectorXd r(m);
    Eigen::MatrixXd j(m, nf);
    std::vector<double> row_major(static_cast<std::size_t>(m) * nf);
    if (!problem.evaluate(problem.natural(), r.data(), row_major.data())) break;
    std::vector<int> lin, non;
    // Only the linear parameters inside their bounds move with the projection (NNLS holds one on
    // its bound, e.g. the relaxed modulus on its floor).
    for (int k = 0; k < nf; ++k) {
      const int i = problem.free()[k];
      const double v = problem.natural()[i];
      if (!problem.specs()[i].linear) non.push_back(k);
      else if (v > problem.lower(i) * (1.0 + 1e-12) + 1e-300 && v < problem.upper(i) * (1.0 - 1e-12)) lin.push_back(k);
    }
    if (non.empty()) {
      out.converged = true;
      break;
    }
    Eigen::MatrixXd jl(m, lin.size()), jt(m, non.size());
    for (int e = 0; e < m; ++e) {
      for (std::size_t c = 0; c < lin.size(); ++c) jl(e, c) = row_major[e * nf + lin[c]];
      for (std::size_t c = 0; c < non.size(); ++c) jt(e, c) = row_major[e * nf + non[c]];
    }
    Eigen::VectorXd x = problem.to_x(problem.natural());
    bool accepted = false;
    for (int attempt = 0; attempt < 24 && !accepted; ++attempt) {
      const Eigen::VectorXd step = lm_step(jt, jl, r, mu);
      Eigen::VectorXd trial = x;
      for (std::size_t c = 0; c < non.size(); ++c) {
        const int k = non[c];
        trial[k] = std::clamp(x[k] + step[c], problem.lower_x(k), problem.upper_x(k));
      }
      const std::vector<int> moving = problem.free();
      problem.from_x(trial.data(), problem.natural());
      const double next = project(problem, all);
      if (next < cost) {
        const double gain = (cost - next) / cost;
        cost = next;
        best = problem.natural();
        accepted = true;
        mu = std::max(mu * 0.1, 1e-9);
        if (gain < kGain) out.converged = true;
      } else {
        problem.natural() = best;
        problem.set_free(moving);
        mu *= 4.0;
      }
    }
    if (!accepted) out.converged = true;  // no descent left at any damping
    if (out.converged) break;
  }
  problem.natural() = best;
  problem.set_free(all);
  std::ostringstream s;
  s << "variable projection: " << nonlinear.size() << " non-linear parameters, " << out.iterations
    << " iterations, cost " << cost << (out.converged ? "" : " (iteration limit)");
  out.note = s.str();
  return out;
}

}  // namespace fitlib::fit::detail
