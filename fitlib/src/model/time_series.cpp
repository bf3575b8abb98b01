#include "fitlib/model/time_series.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/units.hpp"

namespace fitlib::model {
namespace {

// (1 − e^{−x})/x without cancellation for small x.
double one_minus_exp_over(double x) { return x < 1e-8 ? 1.0 - 0.5 * x : -std::expm1(-x) / x; }

// Log-spaced grid from 0 to t: first step to t_first, then `per_decade` points per decade.
std::vector<double> log_grid(double t_first, double t_end, int per_decade) {
  std::vector<double> grid{0.0};
  if (t_end <= 0.0) return grid;
  t_first = std::min(t_first, t_end);
  const int n = std::max(1, static_cast<int>(std::ceil(std::log10(t_end / t_first) * per_decade)));
  for (int k = 0; k <= n; ++k) grid.push_back(t_first * std::pow(t_end / t_first, double(k) / n));
  grid.back() = t_end;
  return grid;
}

}  // namespace

double MaxwellSeries::glassy() const {
  double m = relaxed;
  for (double mi : moduli) m += mi;
  return m;
}

double MaxwellSeries::relaxation(double t_s) const {
  double m = relaxed;
  for (size_t i = 0; i < moduli.size(); ++i) m += moduli[i] * std::exp(-t_s / times_s[i]);
  return m;
}

std::vector<double> MaxwellSeries::stress(const StrainHistory& history) const {
  check_strain_history(history);
  std::vector<double> sigma(history.time_s.size());
  if (sigma.empty()) return sigma;
  std::vector<double> h(moduli.size());
  for (size_t i = 0; i < moduli.size(); ++i) h[i] = moduli[i] * history.strain[0];
  auto total = [&](double eps) {
    double s = relaxed * eps;
    for (double hi : h) s += hi;
    return s;
  };
  sigma[0] = total(history.strain[0]);
  for (size_t n = 1; n < sigma.size(); ++n) {
    const double dt = history.time_s[n] - history.time_s[n - 1];
    const double deps = history.strain[n] - history.strain[n - 1];
    for (size_t i = 0; i < moduli.size(); ++i) {
      const double x = dt / times_s[i];
      h[i] = std::exp(-x) * h[i] + moduli[i] * one_minus_exp_over(x) * deps;
    }
    sigma[n] = total(history.strain[n]);
  }
  return sigma;
}

double MaxwellSeries::creep(double t_s, int steps_per_decade) const {
  const double glassy_modulus = glassy();
  if (!(glassy_modulus > 0.0)) throw core::NumericalError("creep: glassy modulus is not positive");
  double eps = 1.0 / glassy_modulus;
  std::vector<double> h(moduli.size());
  for (size_t i = 0; i < moduli.size(); ++i) h[i] = moduli[i] * eps;
  const double tau_min = times_s.empty() ? 1.0 : *std::min_element(times_s.begin(), times_s.end());
  const auto grid = log_grid(1e-3 * tau_min, t_s, steps_per_decade);
  for (size_t n = 1; n < grid.size(); ++n) {
    const double dt = grid[n] - grid[n - 1];
    double decayed = 0.0, stiffness = relaxed;
    std::vector<double> b(moduli.size());
    for (size_t i = 0; i < moduli.size(); ++i) {
      const double x = dt / times_s[i];
      b[i] = moduli[i] * one_minus_exp_over(x);
      h[i] *= std::exp(-x);
      decayed += h[i];
      stiffness += b[i];
    }
    // Unit stress held: 1 = M_inf ε' + Σ (decayed h_i + b_i (ε' − ε)).
    double rhs = 1.0 - decayed;
    for (double bi : b) rhs += bi * eps;
    const double next = rhs / stiffness;
    for (size_t i = 0; i < moduli.size(); ++i) h[i] += b[i] * (next - eps);
    eps = next;
  }
  return eps;
}

MaxwellSeries three_parameter_solid(double S, double tau_T_s, double tau_eps_s) {
  return {S, {S * (tau_eps_s / tau_T_s - 1.0)}, {tau_T_s}};
}

double KelvinSeries::creep(double t_s) const {
  double j = glassy_compliance;
  for (size_t i = 0; i < compliances.size(); ++i)
    j += compliances[i] * -std::expm1(-t_s / times_s[i]);
  return j;
}

namespace {
// One Kelvin step with stress linear over the step: q_{n+1} = e q_n + L (A σ_n + B σ_{n+1}).
struct KelvinStep {
  std::vector<double> e, a, b;
  KelvinStep(const KelvinSeries& s, double dt) {
    for (size_t i = 0; i < s.times_s.size(); ++i) {
      const double x = dt / s.times_s[i];
      const double ex = std::exp(-x), w = one_minus_exp_over(x);
      e.push_back(ex);
      b.push_back(1.0 - w);   // B = 1 − (λ/Δt)(1 − e)
      a.push_back(w - ex);    // A = (1 − e) − B
    }
  }
  // Stress reaching `strain` at the end of the step; updates q.
  double solve(const KelvinSeries& s, std::vector<double>& q, double sigma_old, double strain) const {
    double known = 0.0, compliance = s.glassy_compliance;
    for (size_t i = 0; i < q.size(); ++i) {
      known += e[i] * q[i] + s.compliances[i] * a[i] * sigma_old;
      compliance += s.compliances[i] * b[i];
    }
    const double sigma = (strain - known) / compliance;
    for (size_t i = 0; i < q.size(); ++i)
      q[i] = e[i] * q[i] + s.compliances[i] * (a[i] * sigma_old + b[i] * sigma);
    return sigma;
  }
};
}  // namespace

std::vector<double> KelvinSeries::stress(const StrainHistory& history) const {
  check_strain_history(history);
  if (!(glassy_compliance > 0.0))
    throw core::NumericalError("retardation spectrum: glassy compliance J_g must be positive");
  std::vector<double> sigma(history.time_s.size());
  if (sigma.empty()) return sigma;
  std::vector<double> q(compliances.size(), 0.0);
  sigma[0] = history.strain[0] / glassy_compliance;
  for (size_t n = 1; n < sigma.size(); ++n) {
    const KelvinStep step(*this, history.time_s[n] - history.time_s[n - 1]);
    sigma[n] = step.solve(*this, q, sigma[n - 1], history.strain[n]);
  }
  return sigma;
}

double KelvinSeries::relaxation(double t_s, int steps_per_decade) const {
  if (!(glassy_compliance > 0.0))
    throw core::NumericalError("retardation spectrum: glassy compliance J_g must be positive");
  std::vector<double> q(compliances.size(), 0.0);
  double sigma = 1.0 / glassy_compliance;
  const double lambda_min =
      times_s.empty() ? 1.0 : *std::min_element(times_s.begin(), times_s.end());
  const auto grid = log_grid(1e-3 * lambda_min, t_s, steps_per_decade);
  for (size_t n = 1; n < grid.size(); ++n)
    sigma = KelvinStep(*this, grid[n] - grid[n - 1]).solve(*this, q, sigma, 1.0);
  return sigma;
}

MaxwellSeries KelvinSeries::to_maxwell() const {
  if (!(glassy_compliance > 0.0))
    throw core::UsageError("retardation spectrum: glassy compliance J_g must be positive");
  // Rates r = 1/λ ascending, equal retardation times merged.
  std::vector<std::pair<double, double>> rate_compliance;
  for (size_t i = 0; i < times_s.size(); ++i) {
    if (!(times_s[i] > 0.0) || !(compliances[i] > 0.0))
      throw core::UsageError("retardation spectrum: L_i and lambda_i must be > 0 for a Maxwell form");
    rate_compliance.push_back({1.0 / times_s[i], compliances[i]});
  }
  std::sort(rate_compliance.begin(), rate_compliance.end());
  // A term below 1e-12 of the total compliance changes J(t) by less than that, but its zero sits
  // within round-off of its rate, where the residue below cannot be resolved (a fitted L_i of
  // 2e-308 gave a Maxwell term of 4e6 MPa on a 1 MPa material): it is left out.
  double total_compliance = glassy_compliance;
  for (const auto& rc : rate_compliance) total_compliance += rc.second;
  std::vector<double> rate, L;
  for (const auto& [r, l] : rate_compliance) {
    if (l <= 1e-12 * total_compliance) continue;
    if (!rate.empty() && r == rate.back()) L.back() += l;
    else rate.push_back(r), L.push_back(l);
  }
  // g(x) = J_g + Σ L_i/(1 − x/r_i) is s·J̄(s) at s = −x; it rises from −∞ to +∞ between
  // consecutive rates and from −∞ to J_g beyond the largest: one zero in each interval.
  auto g = [&](double x) {
    double v = glassy_compliance;
    for (size_t i = 0; i < rate.size(); ++i) v += L[i] / (1.0 - x / rate[i]);
    return v;
  };
  MaxwellSeries m;
  m.relaxed = 1.0 / total_compliance;
  for (size_t k = 0; k < rate.size(); ++k) {
    double lo = rate[k], hi = k + 1 < rate.size() ? rate[k + 1] : 2.0 * rate[k];
    while (k + 1 == rate.size() && g(hi) < 0.0) hi *= 2.0;
    for (int it = 0; it < 200; ++it) {  // bisection to the last bit
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      (g(mid) < 0.0 ? lo : hi) = mid;
    }
    const double x = 0.5 * (lo + hi);
    // Residue of 1/(s J̄(s)) at s = −x gives M_k = τ_k / Σ L_i λ_i/(1 − x λ_i)², τ_k = 1/x.
    double slope = 0.0;
    for (size_t i = 0; i < rate.size(); ++i) {
      const double d = 1.0 - x / rate[i];
      slope += L[i] / rate[i] / (d * d);
    }
    m.times_s.push_back(1.0 / x);
    m.moduli.push_back(1.0 / (x * slope));
  }
  return m;
}

Moduli<double> steady_state_by_time_integration(const Model& model, const double* p,
                                                const TestCondition& c, int cycles,
                                                int steps_per_cycle) {
  const double omega = core::angular_frequency(c.frequency_Hz);
  const double amplitude = c.strain_amplitude > 0.0 ? c.strain_amplitude : 1e-3;
  const int n = cycles * steps_per_cycle;
  StrainHistory history;
  history.time_s.resize(n + 1);
  history.strain.resize(n + 1);
  const double period = 1.0 / c.frequency_Hz;
  for (int k = 0; k <= n; ++k) {
    const double t = period * k / steps_per_cycle;
    history.time_s[k] = t;
    history.strain[k] = c.mean_strain + amplitude * std::sin(omega * t);
  }
  const auto sigma = model.stress_response(p, c, history);
  const int first = n - steps_per_cycle;
  const double t_mid = history.time_s[first] + 0.5 * period;
  Eigen::MatrixXd basis(steps_per_cycle, 4);
  Eigen::VectorXd rhs(steps_per_cycle);
  for (int k = 0; k < steps_per_cycle; ++k) {
    const double t = history.time_s[first + k];
    basis.row(k) << 1.0, (t - t_mid) / period, amplitude * std::sin(omega * t),
        amplitude * std::cos(omega * t);
    rhs(k) = sigma[first + k];
  }
  const Eigen::Vector4d coef = basis.colPivHouseholderQr().solve(rhs);
  const double mean = c.mean_strain != 0.0 ? coef(0) / c.mean_strain
                                           : std::numeric_limits<double>::quiet_NaN();
  return {coef(2), coef(3), mean};
}

}  // namespace fitlib::model
