#include "fitlib/fit/nnls.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace fitlib::fit {

namespace {

// Lawson–Hanson on the column-scaled problem. `solve_passive(P)` returns the unconstrained
// least-squares solution on the passive columns P.
template <class SolvePassive>
Eigen::VectorXd active_set(const Eigen::VectorXd& gradient_at_zero,
                           const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& gradient,
                           int n, int max_iterations, double tol, SolvePassive solve_passive,
                           int& iterations) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  std::vector<bool> passive(n, false);
  Eigen::VectorXd w = gradient_at_zero;
  iterations = 0;
  while (iterations < max_iterations) {
    int best = -1;
    double best_w = tol;
    for (int j = 0; j < n; ++j)
      if (!passive[j] && w[j] > best_w) {
        best_w = w[j];
        best = j;
      }
    if (best < 0) break;
    passive[best] = true;
    for (;;) {
      ++iterations;
      std::vector<int> p;
      for (int j = 0; j < n; ++j)
        if (passive[j]) p.push_back(j);
      const Eigen::VectorXd s_p = solve_passive(p);
      bool feasible = true;
      for (int k = 0; k < static_cast<int>(p.size()); ++k)
        if (!(s_p[k] > 0.0)) feasible = false;
      if (feasible) {
        x.setZero();
        for (int k = 0; k < static_cast<int>(p.size()); ++k) x[p[k]] = s_p[k];
        break;
      }
      // Step from x towards s until the first passive variable reaches zero; it leaves P.
      double alpha = 1.0;
      int blocking = -1;
      for (int k = 0; k < static_cast<int>(p.size()); ++k)
        if (!(s_p[k] > 0.0)) {
          const double xi = x[p[k]];
          const double a = xi > 0.0 ? xi / (xi - s_p[k]) : 0.0;
          if (blocking < 0 || a < alpha) {
            alpha = a;
            blocking = p[k];
          }
        }
      for (int k = 0; k < static_cast<int>(p.size()); ++k) x[p[k]] += alpha * (s_p[k] - x[p[k]]);
      x[blocking] = 0.0;
      const double zero_tol = 1e-14 * std::max(1.0, x.cwiseAbs().maxCoeff());
      for (int j : p)
        if (x[j] <= zero_tol) {
          passive[j] = false;
          x[j] = 0.0;
        }
      if (iterations >= max_iterations) break;
    }
    w = gradient(x);
  }
  return x;
}

// Largest violation of the KKT conditions of min ‖A x − b‖, x ≥ 0 (negative x, positive
// gradient at a bound, any gradient off it).
double kkt_violation(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& x) {
  const Eigen::VectorXd g = a.transpose() * (b - a * x);
  double violation = 0.0;
  for (int j = 0; j < static_cast<int>(x.size()); ++j) {
    if (x[j] < 0.0) violation = std::max(violation, -x[j]);
    if (x[j] == 0.0) violation = std::max(violation, g[j]);
    else violation = std::max(violation, std::abs(g[j]));
  }
  return violation;
}

// The fast path: passive solves on the normal equations (LDLT of AᵀA).
Eigen::VectorXd active_set_normal(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                                  int max_iterations, double tol, int& iterations) {
  const int n = static_cast<int>(a.cols());
  const Eigen::MatrixXd ata = a.transpose() * a;
  const Eigen::VectorXd atb = a.transpose() * b;
  auto gradient = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd { return atb - ata * x; };
  auto solve = [&](const std::vector<int>& p) {
    const int k = static_cast<int>(p.size());
    Eigen::MatrixXd m(k, k);
    Eigen::VectorXd r(k);
    for (int i = 0; i < k; ++i) {
      r[i] = atb[p[i]];
      for (int j = 0; j < k; ++j) m(i, j) = ata(p[i], p[j]);
    }
    return Eigen::VectorXd(m.ldlt().solve(r));
  };
  return active_set(atb, gradient, n, max_iterations, tol, solve, iterations);
}

// The fallback when the normal equations lose too much: passive solves by pivoted QR of A.
Eigen::VectorXd active_set_qr(const Eigen::MatrixXd& a, const Eigen::VectorXd& b,
                              int max_iterations, double tol, int& iterations) {
  const int n = static_cast<int>(a.cols());
  auto gradient = [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
    return a.transpose() * (b - a * x);
  };
  auto solve = [&](const std::vector<int>& p) {
    Eigen::MatrixXd m(a.rows(), static_cast<int>(p.size()));
    for (int k = 0; k < static_cast<int>(p.size()); ++k) m.col(k) = a.col(p[k]);
    return Eigen::VectorXd(m.colPivHouseholderQr().solve(b));
  };
  return active_set(gradient(Eigen::VectorXd::Zero(n)), gradient, n, max_iterations, tol, solve,
                    iterations);
}

}  // namespace

NnlsResult nnls(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, int max_iterations) {
  const int n = static_cast<int>(a.cols());
  NnlsResult result;
  if (max_iterations <= 0) max_iterations = 3 * n + 10;
  // Column scaling: unit column norms make the tolerances meaningful; zero columns stay zero.
  Eigen::VectorXd scale(n);
  for (int j = 0; j < n; ++j) {
    const double norm = a.col(j).norm();
    scale[j] = norm > 0.0 ? 1.0 / norm : 0.0;
  }
  const Eigen::MatrixXd as = a * scale.asDiagonal();
  const double tol = 1e-10 * std::max(b.norm(), 1e-300);
  int iterations = 0;
  Eigen::VectorXd xs = active_set_normal(as, b, max_iterations, tol, iterations);
  double violation = kkt_violation(as, b, xs);
  const double accept = 1e-7 * std::max(b.norm(), 1e-300);
  if (!(violation <= accept) || !xs.allFinite()) {
    int qr_iterations = 0;
    xs = active_set_qr(as, b, max_iterations, tol, qr_iterations);
    iterations += qr_iterations;
    violation = kkt_violation(as, b, xs);
    result.used_qr = true;
  }
  result.x = scale.asDiagonal() * xs;
  for (int j = 0; j < n; ++j)
    if (!(result.x[j] > 0.0)) result.x[j] = 0.0;
  result.residual_norm = (a * result.x - b).norm();
  result.iterations = iterations;
  result.kkt_violation = violation;
  result.converged = violation <= accept && result.x.allFinite();
  return result;
}

}  // namespace fitlib::fit
