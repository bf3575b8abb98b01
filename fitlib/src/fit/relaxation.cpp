// Relaxation-modulus fits (docs/fitting.md, "Relaxation data").
#include "fitlib/fit/relaxation.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/timer.hpp"
#include "fitlib/fit/nnls.hpp"
#include "term_sweep.hpp"

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

// r_i = √w_i (log10 M(t_i) − log10 M_i); Jacobian by central differences in x (step ∝ |x|).
class LogResidual : public ceres::CostFunction {
 public:
  LogResidual(const model::Model& model, const data::RelaxationTable& table, const Coordinates& coords,
              std::vector<double> natural)
      : model_(model), table_(table), coords_(coords), natural_(std::move(natural)) {
    set_num_residuals(static_cast<int>(table.rows.size()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(coords.free.size()));
  }

  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    std::vector<double> p = natural_at(x[0]);
    if (!residuals_at(p, residuals)) return false;
    if (!jacobians || !jacobians[0]) return true;
    const int m = num_residuals(), n = static_cast<int>(coords_.free.size());
    std::vector<double> up(m), down(m);
    for (int k = 0; k < n; ++k) {
      const int i = coords_.free[k];
      const double h = 1e-6 * std::max(1.0, std::abs(x[0][k]));
      std::vector<double> q = p;
      q[i] = coords_.from_x(i, x[0][k] + h);
      if (!residuals_at(q, up.data())) return false;
      q[i] = coords_.from_x(i, x[0][k] - h);
      if (!residuals_at(q, down.data())) return false;
      for (int r = 0; r < m; ++r) jacobians[0][r * n + k] = (up[r] - down[r]) / (2.0 * h);
    }
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
};

model::DataSummary summarize_relaxation(const data::RelaxationTable& table) {
  model::DataSummary s;
  double t_min = HUGE_VAL, t_max = 0.0, m_min = HUGE_VAL, m_max = 0.0;
  s.temperature_min_C = HUGE_VAL;
  s.temperature_max_C = -HUGE_VAL;
  for (const auto& r : table.rows) {
    t_min = std::min(t_min, r.time_s);
    t_max = std::max(t_max, r.time_s);
    m_min = std::min(m_min, r.modulus_MPa);
    m_max = std::max(m_max, r.modulus_MPa);
    if (!std::isnan(r.temperature_C)) {
      s.temperature_min_C = std::min(s.temperature_min_C, r.temperature_C);
      s.temperature_max_C = std::max(s.temperature_max_C, r.temperature_C);
    }
  }
  if (s.temperature_min_C > s.temperature_max_C) s.temperature_min_C = s.temperature_max_C = 23.0;
  // A relaxation time τ is seen at t ≈ τ, as a frequency ω ≈ 1/τ is.
  s.omega_min_rad_s = 1.0 / t_max;
  s.omega_max_rad_s = 1.0 / t_min;
  s.storage_min_MPa = m_min;
  s.storage_max_MPa = m_max;
  return s;
}

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
  const auto& specs = *coords.specs;
  const int nf = static_cast<int>(coords.free.size());
  std::vector<double> x(nf);
  for (int k = 0; k < nf; ++k) x[k] = coords.to_x(coords.free[k], p[coords.free[k]]);
  auto* cost = new LogResidual(model, table, coords, p);
  ceres::Problem problem;
  problem.AddResidualBlock(cost, nullptr, x.data());
  for (int k = 0; k < nf; ++k) {
    const int i = coords.free[k];
    const double lo = coords.is_log(i) ? (specs[i].lower > 0.0 ? std::log(specs[i].lower) : -HUGE_VAL) : specs[i].lower;
    const double hi = coords.is_log(i) ? std::log(specs[i].upper) : specs[i].upper;
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

}  // namespace

FitResult fit_relaxation(const model::ModelPtr& model_ptr, const data::RelaxationTable& table,
                         const FitOptions& options) {
  const core::Stopwatch clock;
  if (table.rows.empty()) throw core::InputError("relaxation fit: no data rows");
  const model::Model& model = *model_ptr;
  const auto& specs = model.parameters();
  std::vector<double> p = model.initial_parameters(summarize_relaxation(table));
  const auto user_fixed = [&](int i) {
    return std::find(options.fixed.begin(), options.fixed.end(), specs[i].name) != options.fixed.end();
  };
  for (const auto& name : options.fixed)
    if (core::find_parameter(specs, name) < 0) throw core::UsageError("--fixed: unknown parameter '" + name + "'");
  std::vector<int> linear;
  for (int i = 0; i < static_cast<int>(specs.size()); ++i)
    if (specs[i].linear && !user_fixed(i)) linear.push_back(i);
  solve_linear(model, table, linear, p);

  FitResult result;
  result.model = model_ptr;
  result.objective = "sum of squared log10 errors of the relaxation modulus M(t)";
  result.backend_used = "nnls";
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

TermSelection select_relaxation_terms(const std::string& kind, const nlohmann::json& model_options,
                                      const data::RelaxationTable& table, const FitOptions& options,
                                      const TermOptions& terms) {
  int max_terms = terms.max_terms;
  if (max_terms <= 0) {
    const auto s = summarize_relaxation(table);
    max_terms = std::clamp(static_cast<int>(std::ceil(std::log10(s.omega_max_rad_s / s.omega_min_rad_s))) + 2, 1, 40);
  }
  const int min_terms = std::max(terms.min_terms, 1);
  if (max_terms < min_terms) throw core::UsageError("relaxation terms: max below min");
  TermSelection sel;
  sel.rule = terms.rule;
  // Each N is ranked on its linear solve (τ on the model's start grid); only the chosen N is
  // polished, so the search costs one polish (docs/fitting.md, "Relaxation data").
  FitOptions linear_only = options;
  linear_only.polish = false;
  auto fit_n = [&](int n) {
    nlohmann::json o = model_options.is_object() ? model_options : nlohmann::json::object();
    o["terms"] = n;
    return fit_relaxation(model::make_model(kind, o), table, linear_only);
  };
  std::vector<FitResult> results = detail::sweep_terms(min_terms, max_terms, fit_n, terms, false, sel);
  sel.unconstrained = choose_terms(sel.rows, terms.rule, terms.residual_ratio, 0);
  sel.chosen = choose_terms(sel.rows, terms.rule, terms.residual_ratio, terms.solver_cap);
  if (sel.chosen == 0) throw core::NumericalError("relaxation terms: no usable fit");
  sel.result = options.polish ? fit_relaxation(results[sel.chosen - min_terms].model, table, options)
                              : std::move(results[sel.chosen - min_terms]);
  return sel;
}

}  // namespace fitlib::fit
