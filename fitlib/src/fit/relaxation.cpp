// Relaxation-modulus fits (docs/fitting.md, "Relaxation data").
#include "fitlib/fit/relaxation.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/timer.hpp"
#include "fitlib/fit/nnls.hpp"
#include "admissible.hpp"
#include "quality.hpp"
#include "relaxation_checks.hpp"

namespace fitlib::fit {
namespace {

model::TestCondition condition_of(const data::RelaxationRow& row) {
  model::TestCondition c;
  c.mode = row.mode;
  c.temperature_C = row.temperature_C;
  return c;
}

// The free parameters in fitted coordinates (ln p for log-transformed ones).
struct Coordinates {
  const std::vector<core::ParameterSpec>* specs;
  std::vector<int> free;
  bool is_log(int i) const { return (*specs)[i].transform == core::Transform::log; }
  double to_x(int i, double v) const { return is_log(i) ? std::log(v) : v; }
  double from_x(int i, double x) const { return is_log(i) ? std::exp(x) : x; }
};

// Role of each free parameter in M(t) = E∞ + Σ E_j exp(−t/τ_j) when the model's relaxation
// modulus is that plain series (no law, native mode; checked numerically by plain_series_roles),
// so that its derivative is analytic; kNumeric for the others.
constexpr int kNumeric = -1, kRelaxed = -2;
struct Role {
  int term = kNumeric;  // j ≥ 0: term j's modulus or time; kRelaxed; kNumeric
  bool time = false;
};

double plain_series(const detail::SeriesTerms& s, const double* p, double t) {
  double m = s.relaxed >= 0 ? p[s.relaxed] : 0.0;
  for (std::size_t j = 0; j < s.times.size(); ++j) m += p[s.moduli[j]] * std::exp(-t / p[s.times[j]]);
  return m;
}

std::vector<Role> plain_series_roles(const model::Model& model, const data::RelaxationTable& table,
                                     const std::vector<int>& free, std::vector<double> p) {
  std::vector<Role> roles(free.size());
  const detail::SeriesTerms s = detail::series_terms(model.parameters());
  if (s.empty() || model.temperature_law_info().law != model::ShiftLaw::none) return roles;
  for (int i : s.moduli) p[i] = 1.0;  // every term visible in the check
  if (s.relaxed >= 0) p[s.relaxed] = 1.0;
  for (const auto& row : table.rows) {
    if (row.mode != model.native_mode()) return roles;
    const double want = model.relaxation_modulus(p.data(), condition_of(row), row.time_s);
    if (!(std::abs(plain_series(s, p.data(), row.time_s) - want) <= 1e-12 * std::abs(want))) return roles;
  }
  for (std::size_t k = 0; k < free.size(); ++k) {
    if (free[k] == s.relaxed) roles[k].term = kRelaxed;
    for (std::size_t j = 0; j < s.times.size(); ++j) {
      if (free[k] == s.moduli[j]) roles[k].term = static_cast<int>(j);
      if (free[k] == s.times[j]) roles[k] = {static_cast<int>(j), true};
    }
  }
  return roles;
}

// r_i = √w_i (log10 M(t_i) − log10 M_i); the Jacobian in x analytic for the plain series'
// parameters, by central differences (step ∝ |x|) for the others.
class LogResidual : public ceres::CostFunction {
 public:
  LogResidual(const model::Model& model, const data::RelaxationTable& table, const Coordinates& coords,
              std::vector<double> natural)
      : model_(model), table_(table), coords_(coords), natural_(std::move(natural)),
        series_(detail::series_terms(model.parameters())),
        roles_(plain_series_roles(model, table, coords.free, natural_)) {
    set_num_residuals(static_cast<int>(table.rows.size()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(coords.free.size()));
  }

  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    std::vector<double> p = natural_at(x[0]);
    if (!residuals_at(p, residuals)) return false;
    if (!jacobians || !jacobians[0]) return true;
    series_columns(p, jacobians[0]);
    for (int k = 0; k < static_cast<int>(coords_.free.size()); ++k)
      if (roles_[k].term == kNumeric && !numeric_column(p, x[0], k, jacobians[0])) return false;
    return true;
  }

  // ∂r_i/∂x_k = √w_i ∂M/∂p · (dp/dx) / (M ln 10) for the plain series' parameters, one row at
  // a time (each term's exponential computed once).
  void series_columns(const std::vector<double>& p, double* jac) const {
    const int n = static_cast<int>(coords_.free.size()), terms = static_cast<int>(series_.times.size());
    std::vector<double> decay(terms);
    for (std::size_t r = 0; r < table_.rows.size(); ++r) {
      const auto& row = table_.rows[r];
      double m = series_.relaxed >= 0 ? p[series_.relaxed] : 0.0;
      for (int j = 0; j < terms; ++j) {
        decay[j] = std::exp(-row.time_s / p[series_.times[j]]);
        m += p[series_.moduli[j]] * decay[j];
      }
      const double scale = std::sqrt(row.weight) / (m * std::log(10.0));
      for (int k = 0; k < n; ++k) {
        const Role role = roles_[k];
        if (role.term == kNumeric) continue;
        const int i = coords_.free[k];
        double dm = role.term == kRelaxed ? 1.0 : decay[role.term];
        if (role.time) {
          const double tau = p[series_.times[role.term]];
          dm *= p[series_.moduli[role.term]] * row.time_s / (tau * tau);
        }
        jac[r * n + k] = scale * dm * (coords_.is_log(i) ? p[i] : 1.0);
      }
    }
  }

  bool numeric_column(const std::vector<double>& p, const double* x, int k, double* jac) const {
    const int m = num_residuals(), n = static_cast<int>(coords_.free.size()), i = coords_.free[k];
    std::vector<double> up(m), down(m);
    const double h = 1e-6 * std::max(1.0, std::abs(x[k]));
    std::vector<double> q = p;
    q[i] = coords_.from_x(i, x[k] + h);
    if (!residuals_at(q, up.data())) return false;
    q[i] = coords_.from_x(i, x[k] - h);
    if (!residuals_at(q, down.data())) return false;
    for (int r = 0; r < m; ++r) jac[r * n + k] = (up[r] - down[r]) / (2.0 * h);
    return true;
  }

  std::vector<double> natural_at(const double* x) const {
    std::vector<double> p = natural_;
    for (std::size_t k = 0; k < coords_.free.size(); ++k) p[coords_.free[k]] = coords_.from_x(coords_.free[k], x[k]);
    return p;
  }

  bool residuals_at(const std::vector<double>& p, double* r) const {
    for (std::size_t i = 0; i < table_.rows.size(); ++i) {
      const auto& row = table_.rows[i];
      const double m = model_.relaxation_modulus(p.data(), condition_of(row), row.time_s);
      if (!(m > 0.0) || !std::isfinite(m)) return false;
      r[i] = std::sqrt(row.weight) * (std::log10(m) - std::log10(row.modulus_MPa));
    }
    return true;
  }

 private:
  const model::Model& model_;
  const data::RelaxationTable& table_;
  const Coordinates& coords_;
  std::vector<double> natural_;
  detail::SeriesTerms series_;
  std::vector<Role> roles_;
};

// Non-negative weights of the linear parameters with the others held: rows scaled by 1/M_i
// (first-order form of the log10 residual).
void solve_linear(const model::Model& model, const data::RelaxationTable& table, const std::vector<int>& linear,
                  std::vector<double>& p) {
  if (linear.empty()) return;
  const int m = static_cast<int>(table.rows.size()), n = static_cast<int>(linear.size());
  std::vector<double> q = p;
  for (int j : linear) q[j] = 0.0;
  Eigen::MatrixXd a(m, n);
  Eigen::VectorXd b(m);
  for (int i = 0; i < m; ++i) {
    const auto& row = table.rows[i];
    const auto c = condition_of(row);
    const double base = model.relaxation_modulus(q.data(), c, row.time_s);
    const double w = std::sqrt(row.weight) / row.modulus_MPa;
    b[i] = w * (row.modulus_MPa - base);
    for (int k = 0; k < n; ++k) {
      q[linear[k]] = 1.0;
      a(i, k) = w * (model.relaxation_modulus(q.data(), c, row.time_s) - base);
      q[linear[k]] = 0.0;
    }
  }
  const NnlsResult s = nnls(a, b);
  if (!s.x.allFinite()) throw core::NumericalError("relaxation fit: the linear solve failed");
  for (int k = 0; k < n; ++k) p[linear[k]] = s.x[k];
}

}  // namespace

RelaxationMeasures measure_relaxation(const model::Model& model, const std::vector<double>& p,
                                      const data::RelaxationTable& table) {
  RelaxationMeasures out;
  double s_log = 0.0, s_rel = 0.0, sum_rel = 0.0;
  for (const auto& row : table.rows) {
    const double m = model.relaxation_modulus(p.data(), condition_of(row), row.time_s);
    const double rel = (m - row.modulus_MPa) / row.modulus_MPa;
    const double lg = std::log10(m / row.modulus_MPa);
    s_log += lg * lg;
    s_rel += rel * rel;
    sum_rel += std::abs(rel);
    out.max_relative = std::max(out.max_relative, std::abs(rel));
  }
  const double n = static_cast<double>(table.rows.size());
  out.rms_log10 = std::sqrt(s_log / n);
  out.rms_relative = std::sqrt(s_rel / n);
  out.mean_relative = sum_rel / n;
  return out;
}

namespace {

// Log-space Levenberg-Marquardt polish of the free parameters from the linear solve, inside the
// parameters' bounds; an unusable solve keeps the linear one, with a message.
void polish_relaxation(const model::Model& model, const data::RelaxationTable& table,
                       const Coordinates& coords, const FitOptions& options, std::vector<double>& p,
                       FitResult& result) {
  const int nf = static_cast<int>(coords.free.size());
  std::vector<double> x(nf);
  for (int k = 0; k < nf; ++k) x[k] = coords.to_x(coords.free[k], p[coords.free[k]]);
  auto* cost = new LogResidual(model, table, coords, p);
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, x.data());
  for (int k = 0; k < nf; ++k) {
    const int i = coords.free[k];
    const auto [lower, upper] = detail::window_bounds(model, result.admissible, i);
    const double lo = coords.is_log(i) ? (lower > 0.0 ? std::log(lower) : -HUGE_VAL) : lower;
    const double hi = coords.is_log(i) ? std::log(upper) : upper;
    if (std::isfinite(lo)) problem.SetParameterLowerBound(x.data(), k, lo);
    if (std::isfinite(hi)) problem.SetParameterUpperBound(x.data(), k, hi);
  }
  ceres::Solver::Options so;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.use_nonmonotonic_steps = true;
  so.num_threads = 1;  // determinism
  so.max_num_iterations = options.max_iterations;
  so.function_tolerance = options.tolerance;
  so.parameter_tolerance = 1e-10;
  so.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  if (summary.IsSolutionUsable()) {
    p = cost->natural_at(x.data());
    result.backend_used = "nnls+ceres";
    result.metrics.converged = summary.termination_type == ceres::CONVERGENCE;
    result.metrics.iterations = static_cast<int>(summary.iterations.size());
  } else {
    result.messages.push_back("relaxation polish: no usable solution (" + summary.message + "); linear solve kept");
  }
}

// Cost, errors and information criteria of the fitted relaxation modulus; a log parameter at 0 is
// an inactive term and does not count as free.
void measure_fit(const model::Model& model, const data::RelaxationTable& table,
                 const Coordinates& coords, const std::vector<double>& p, FitMetrics& mt) {
  const int m = static_cast<int>(table.rows.size());
  const RelaxationMeasures measures = measure_relaxation(model, p, table);
  double cost = 0.0;
  for (const auto& row : table.rows) {
    const double r = std::log10(model.relaxation_modulus(p.data(), condition_of(row), row.time_s) / row.modulus_MPa);
    cost += 0.5 * row.weight * r * r;
  }
  int active = 0;
  for (int i : coords.free) active += coords.is_log(i) ? p[i] > 0.0 : 1;
  mt.n_points = m;
  mt.n_residuals = m;
  mt.n_free = active;
  mt.cost = cost;
  mt.rms_log10_storage = measures.rms_log10;
  mt.mean_rel_error = measures.mean_relative;
  mt.max_rel_error = measures.max_relative;
  const double variance = std::max(2.0 * cost / m, 1e-300);
  mt.aic = m * std::log(variance) + 2.0 * active;
  mt.bic = m * std::log(variance) + active * std::log(static_cast<double>(m));
}

// The linear solve's values moved into the admissible window (a relaxed modulus the solve left
// at 0 goes to its floor and stays free), with a message saying so.
template <typename Fixed>
void hold_in_window(const model::Model& model, const AdmissibleWindow& w, const Fixed& user_fixed,
                    std::vector<double>& p, FitResult& result) {
  if (!w.applies) return;
  int moved = 0;
  for (int i = 0; i < static_cast<int>(p.size()); ++i) {
    if (user_fixed(i)) continue;
    const auto [lo, hi] = detail::window_bounds(model, w, i);
    if (model.parameters()[i].transform == core::Transform::log && p[i] == 0.0 && lo <= 0.0)
      continue;  // a term the linear solve left out stays out
    const double held = std::clamp(p[i], lo, hi);
    moved += held != p[i];
    p[i] = held;
  }
  result.messages.push_back(detail::describe_window(w, moved));
}

}  // namespace

FitResult fit_relaxation(const model::ModelPtr& model_ptr, const data::RelaxationTable& table,
                         const FitOptions& options, const std::vector<double>* start) {
  const core::Stopwatch clock;
  if (table.rows.empty()) throw core::InputError("relaxation fit: no data rows");
  const model::Model& model = *model_ptr;
  const auto& specs = model.parameters();
  std::vector<double> p = start ? *start : model.initial_parameters(detail::summarize_relaxation(table));
  if (p.size() != specs.size()) throw core::UsageError("relaxation fit: start has the wrong size");
  const auto user_fixed = [&](int i) {
    return std::find(options.fixed.begin(), options.fixed.end(), specs[i].name) != options.fixed.end();
  };
  for (const auto& name : options.fixed)
    if (core::find_parameter(specs, name) < 0) throw core::UsageError("--fixed: unknown parameter '" + name + "'");
  std::vector<int> linear;
  for (int i = 0; i < static_cast<int>(specs.size()); ++i)
    if (specs[i].linear && !user_fixed(i)) linear.push_back(i);
  if (!start) solve_linear(model, table, linear, p);

  FitResult result;
  result.model = model_ptr;
  result.objective = "sum of squared log10 errors of the relaxation modulus M(t)";
  result.backend_used = "nnls";
  result.admissible = detail::relaxation_window(model, table, options);
  hold_in_window(model, result.admissible, user_fixed, p, result);
  Coordinates coords{&specs, {}};
  for (int i = 0; i < static_cast<int>(specs.size()); ++i) {
    if (user_fixed(i)) continue;
    if (coords.is_log(i) && !(p[i] > 0.0)) continue;  // inactive term after the linear solve
    coords.free.push_back(i);
  }
  if (options.polish && !coords.free.empty())
    polish_relaxation(model, table, coords, options, p, result);
  else
    result.metrics.converged = true;
  for (double v : p)
    if (!std::isfinite(v)) throw core::NumericalError("relaxation fit: a parameter is not finite");
  measure_fit(model, table, coords, p, result.metrics);
  result.quality = detail::relaxation_verdict(model, p, table);
  detail::degrees_of_freedom_warning(result.metrics, result.quality);
  result.values = p;
  for (int i = 0; i < static_cast<int>(specs.size()); ++i) {
    ParameterResult pr;
    pr.name = specs[i].name;
    pr.unit = specs[i].unit;
    pr.value = std::clamp(p[i], specs[i].lower, specs[i].upper);
    pr.fixed = user_fixed(i);
    pr.reason = "standard errors are not estimated for relaxation fits";
    result.parameters.push_back(pr);
    result.values[i] = pr.value;
  }
  result.metrics.wall_time_s = clock.seconds();
  return result;
}

}  // namespace fitlib::fit
