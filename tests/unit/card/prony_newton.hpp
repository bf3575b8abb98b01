#pragma once
// A damped Newton polish of a Prony card on log10 errors with the EXACT Hessian (test helper;
// docs/decisions.md "Term economy: the dense zone's polish in 15 Newton steps; no general rule
// for the zone"). On pyvisco's master the residuals stay large at the optimum (E″ rms log10 ≈ 0.38:
// the data are not Kramers–Kronig consistent), where Gauss–Newton and Levenberg–Marquardt, which
// drop the second-order term Σ r ∇²r, converge only linearly (≈ 120–150 steps, Ceres too). The
// second-order term is cheap here: a Prony sum is additive over terms, so ∇²E′ and ∇²E″ are 2 × 2
// per term in (ln E_k, ln τ_k).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

namespace fitlib::card::testing {

struct Master {  // a master curve: angular frequencies, E′ and E″ (MPa)
  std::vector<double> omega, storage, loss;
};
struct PronyCard {
  double relaxed = 0.0;  // held
  std::vector<double> moduli, times_s;
};

// log10 residuals (E′ ones times √w′) and their Jacobian in (ln E_k for all k, ln τ_k for the free
// times), and per point the values a Newton step needs.
struct Linearised {
  Eigen::VectorXd r;
  Eigen::MatrixXd j;
  std::vector<double> storage, loss;  // the card's E′, E″ at the data's frequencies
};

inline Linearised linearise(const Master& m, const PronyCard& c, const std::vector<int>& free_times, double storage_weight,
                            bool jacobian) {
  const int n = static_cast<int>(m.omega.size()), terms = static_cast<int>(c.moduli.size());
  const double ws = std::sqrt(storage_weight) / std::log(10.0), wl = 1.0 / std::log(10.0);
  Linearised out{Eigen::VectorXd(2 * n), Eigen::MatrixXd(), std::vector<double>(n), std::vector<double>(n)};
  if (jacobian) out.j.resize(2 * n, terms + free_times.size());
  for (int i = 0; i < n; ++i) {
    double e1 = c.relaxed, e2 = 0.0;
    for (int k = 0; k < terms; ++k) {
      const double x = m.omega[i] * c.times_s[k], d = 1.0 + x * x;
      e1 += c.moduli[k] * x * x / d;
      e2 += c.moduli[k] * x / d;
    }
    out.storage[i] = e1, out.loss[i] = e2;
    out.r[i] = ws * std::log(e1 / m.storage[i]);
    out.r[n + i] = wl * std::log(e2 / m.loss[i]);
    if (!jacobian) continue;
    for (int k = 0; k < terms; ++k) {
      const double x = m.omega[i] * c.times_s[k], d = 1.0 + x * x;
      out.j(i, k) = ws * c.moduli[k] * x * x / d / e1;
      out.j(n + i, k) = wl * c.moduli[k] * x / d / e2;
    }
    for (std::size_t f = 0; f < free_times.size(); ++f) {
      const int k = free_times[f];
      const double x = m.omega[i] * c.times_s[k], d = 1.0 + x * x;
      out.j(i, terms + f) = ws * c.moduli[k] * 2.0 * x * x / (d * d) / e1;
      out.j(n + i, terms + f) = wl * c.moduli[k] * x * (1.0 - x * x) / (d * d) / e2;
    }
  }
  return out;
}

// Hessian of ½‖r‖²: with r = c ln S, ∇²r = c ∇²S / S − ∇r∇rᵀ / c, so
// H = Jᵀ diag(1 − r/c) J + Σ r c ∇²S / S, the last 2 × 2 per term.
inline Eigen::MatrixXd hessian_with_second_order(const Master& m, const PronyCard& c, const std::vector<int>& free_times,
                                     double storage_weight, const Linearised& l) {
  const int n = static_cast<int>(m.omega.size()), terms = static_cast<int>(c.moduli.size());
  const double ws = std::sqrt(storage_weight) / std::log(10.0), wl = 1.0 / std::log(10.0);
  Eigen::VectorXd d(2 * n);
  for (int i = 0; i < n; ++i) d[i] = 1.0 - l.r[i] / ws, d[n + i] = 1.0 - l.r[n + i] / wl;
  Eigen::MatrixXd h = l.j.transpose() * d.asDiagonal() * l.j;
  std::vector<int> column(terms, -1);
  for (std::size_t f = 0; f < free_times.size(); ++f) column[free_times[f]] = terms + static_cast<int>(f);
  for (int i = 0; i < n; ++i) {
    const double a1 = l.r[i] * ws / l.storage[i], a2 = l.r[n + i] * wl / l.loss[i];
    for (int k = 0; k < terms; ++k) {
      const double x = m.omega[i] * c.times_s[k], q = 1.0 + x * x, e = c.moduli[k];
      h(k, k) += a1 * e * x * x / q + a2 * e * x / q;  // E′, E″ linear in E_k: ∂²/∂(ln E)² = ∂/∂ln E
      const int v = column[k];
      if (v < 0) continue;
      const double cross = a1 * e * 2.0 * x * x / (q * q) + a2 * e * x * (1.0 - x * x) / (q * q);
      h(k, v) += cross, h(v, k) += cross;
      h(v, v) += a1 * e * 4.0 * x * x * (1.0 - x * x) / (q * q * q) + a2 * e * x * (1.0 - 6.0 * x * x + x * x * x * x) / (q * q * q);
    }
  }
  return h;
}

struct PolishResult {
  int steps = 0;
  double cost = 0.0;  // ‖r‖²
};

// Damped Newton (exact_hessian) or Levenberg–Marquardt (JᵀJ), in ln E_k and ln τ_k of the free
// times (clamped to [tau_min_s, tau_max_s]), the relaxed modulus held; stops when a step lowers
// the cost by less than `relative_fall` of it, or after max_steps.
inline PolishResult polish_log10(const Master& m, PronyCard& c, const std::vector<int>& free_times, double storage_weight,
                                 double tau_min_s, double tau_max_s, bool exact_hessian, int max_steps = 300,
                                 double relative_fall = 1e-6) {
  const int terms = static_cast<int>(c.moduli.size()), np = terms + static_cast<int>(free_times.size());
  for (double& e : c.moduli) e = std::max(e, 1e-9);  // NNLS zeros: ln E needs a positive start
  Linearised l = linearise(m, c, free_times, storage_weight, true);
  PolishResult out{0, l.r.squaredNorm()};
  double mu = -1.0;
  while (out.steps < max_steps) {
    ++out.steps;
    const Eigen::MatrixXd jtj = l.j.transpose() * l.j;
    const Eigen::MatrixXd h = exact_hessian ? hessian_with_second_order(m, c, free_times, storage_weight, l) : jtj;
    const Eigen::VectorXd g = l.j.transpose() * l.r;
    if (mu < 0.0) mu = 1e-3;
    bool accepted = false;
    for (int tries = 0; tries < 40 && !accepted; ++tries) {
      Eigen::MatrixXd b = h;
      for (int p = 0; p < np; ++p) b(p, p) += mu * std::max(jtj(p, p), 1e-12);
      const Eigen::LDLT<Eigen::MatrixXd> ldlt(b);
      if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) {
        mu *= 4.0;
        continue;
      }
      const Eigen::VectorXd step = -ldlt.solve(g);
      PronyCard trial = c;
      for (int k = 0; k < terms; ++k) trial.moduli[k] = c.moduli[k] * std::exp(std::clamp(step[k], -5.0, 5.0));
      for (std::size_t f = 0; f < free_times.size(); ++f) {
        const int k = free_times[f];
        trial.times_s[k] = std::clamp(c.times_s[k] * std::exp(std::clamp(step[terms + f], -2.0, 2.0)), tau_min_s, tau_max_s);
      }
      const double cost = linearise(m, trial, free_times, storage_weight, false).r.squaredNorm();
      if (!(cost < out.cost)) {
        mu *= 4.0;
        continue;
      }
      accepted = true;
      const double fall = (out.cost - cost) / out.cost;
      c = trial;
      out.cost = cost;
      mu = std::max(mu / 3.0, 1e-15);
      if (fall < relative_fall) return out;
    }
    if (!accepted) return out;
    l = linearise(m, c, free_times, storage_weight, true);
  }
  return out;
}

}  // namespace fitlib::card::testing
