#include "backends.hpp"
#include "admissible.hpp"

#include <ceres/ceres.h>
#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/progress.hpp"
#include "fitlib/core/rng.hpp"
#include "fitlib/fit/nnls.hpp"

namespace fitlib::fit::detail {

namespace {

constexpr double kLn10 = 2.302585092994046;
constexpr double kInf = std::numeric_limits<double>::infinity();

// All residuals in one cost function with one parameter block (the free x): the problems are
// small and dense, and the model's Jacobian comes per row for all parameters at once.
class ProblemCost : public ceres::CostFunction {
 public:
  explicit ProblemCost(const Problem& problem) : problem_(problem), natural_(problem.natural()) {
    set_num_residuals(problem.num_residuals());
    mutable_parameter_block_sizes()->push_back(problem.num_free());
  }
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    problem_.from_x(x[0], natural_);
    return problem_.evaluate(natural_, residuals, jacobians ? jacobians[0] : nullptr);
  }

 private:
  const Problem& problem_;
  mutable std::vector<double> natural_;
};

std::string join_names(const Problem& problem, const std::vector<int>& indices) {
  std::string s;
  for (int i : indices) s += (s.empty() ? "" : ", ") + problem.specs()[i].name;
  return s;
}

}  // namespace

std::vector<int> movable(const Problem& problem, const std::vector<int>& candidates) {
  // The time constant of a removed series term (modulus 0) has no effect either.
  const SeriesTerms series = series_terms(problem.specs());
  std::vector<bool> removed(problem.num_parameters(), false);
  for (std::size_t k = 0; k < series.times.size(); ++k)
    removed[series.times[k]] = problem.natural()[series.moduli[k]] == 0.0;
  std::vector<int> out;
  for (int i : candidates)
    if (!(problem.is_log(i) && problem.natural()[i] <= 0.0) && !problem.user_fixed()[i] && !removed[i])
      out.push_back(i);
  return out;
}

LinearDesign linear_design(const Problem& problem) {
  LinearDesign d;
  const auto& specs = problem.specs();
  for (int i : problem.free()) (specs[i].linear ? d.linear : d.held).push_back(i);
  const std::vector<double>& p = problem.natural();
  const int m = problem.num_residuals(), n = problem.num_parameters();
  // Columns: one per linear parameter with a lower bound (shifted to 0), two (±) when unbounded.
  for (int i : d.linear) {
    d.column_param.push_back(i);
    d.column_sign.push_back(1.0);
    if (!std::isfinite(problem.lower(i))) {
      d.column_param.push_back(i);
      d.column_sign.push_back(-1.0);
    }
  }
  const int nc = static_cast<int>(d.column_param.size());
  d.a.resize(m, nc);
  d.b.resize(m);
  Eigen::MatrixXd jac(3, n);
  int current_row = -1;
  model::Moduli<double> mod{};
  for (int e = 0; e < m; ++e) {
    const ResidualEntry& en = problem.entries()[e];
    if (en.row != current_row) {
      current_row = en.row;
      mod = problem.model().moduli(p.data(), problem.table().rows[en.row].condition, jac);
    }
    const double value = en.component == 0 ? mod.storage : en.component == 1 ? mod.loss : mod.mean;
    // Linear parameters: value = offset + Σ jac·p over them, exactly.
    double offset = value;
    for (int i : d.linear) offset -= jac(en.component, i) * p[i];
    const double row_scale = en.sqrt_weight / (en.absolute ? en.scale : en.data * kLn10);
    double rhs = en.data - offset;
    for (int c = 0; c < nc; ++c) {
      const int i = d.column_param[c];
      d.a(e, c) = row_scale * d.column_sign[c] * jac(en.component, i);
    }
    for (int i : d.linear)
      if (std::isfinite(problem.lower(i))) rhs -= jac(en.component, i) * problem.lower(i);
    d.b[e] = row_scale * rhs;
  }
  if (!d.a.allFinite() || !d.b.allFinite())
    throw core::NumericalError("nnls: the design matrix of model '" + problem.model().kind() +
                               "' is not finite at the start (check the fixed time constants)");
  return d;
}

int apply_linear_solution(Problem& problem, const LinearDesign& d, const Eigen::VectorXd& x) {
  if (!x.allFinite())
    throw core::NumericalError("nnls: the non-negative solve produced non-finite moduli");
  std::vector<double>& p = problem.natural();
  for (int i : d.linear) p[i] = std::isfinite(problem.lower(i)) ? problem.lower(i) : 0.0;
  for (std::size_t c = 0; c < d.column_param.size(); ++c) p[d.column_param[c]] += d.column_sign[c] * x[c];
  int clamped = 0;
  for (int i : d.linear)
    if (p[i] > problem.upper(i)) {
      p[i] = problem.upper(i);
      ++clamped;
    }
  return clamped;
}

StageOutcome run_nnls(Problem& problem) {
  StageOutcome outcome;
  const LinearDesign d = linear_design(problem);
  if (d.linear.empty()) {
    outcome.converged = true;
    outcome.note = "nnls: no free linear parameter; nothing to solve";
    return outcome;
  }
  const NnlsResult solved = nnls(d.a, d.b);
  const int clamped = apply_linear_solution(problem, d, solved.x);
  outcome.converged = solved.converged;
  outcome.iterations = solved.iterations;
  std::ostringstream s;
  int zeros = 0;
  for (int i : d.linear) zeros += problem.natural()[i] <= problem.lower(i);
  s << "nnls: " << d.linear.size() << " linear parameters, " << zeros << " at their lower bound, "
    << solved.iterations << " active-set steps" << (solved.used_qr ? " (QR fallback)" : "")
    << ", KKT check " << (solved.converged ? "passed" : "FAILED");
  if (clamped) s << ", " << clamped << " clamped to their upper bound";
  if (!d.held.empty()) s << "; held at start: " << join_names(problem, d.held);
  outcome.note = s.str();
  return outcome;
}

StageOutcome run_ceres(Problem& problem, int max_iterations) {
  StageOutcome outcome;
  const int nf = problem.num_free();
  if (nf == 0) {
    outcome.converged = true;
    return outcome;
  }
  Eigen::VectorXd x = problem.to_x(problem.natural());
  if (!x.allFinite())
    throw core::NumericalError("ceres: start is not finite in fitted coordinates");
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem cp(problem_options);
  cp.AddResidualBlock(new ProblemCost(problem), nullptr, x.data());
  for (int k = 0; k < nf; ++k) {
    if (std::isfinite(problem.lower_x(k))) cp.SetParameterLowerBound(x.data(), k, problem.lower_x(k));
    if (std::isfinite(problem.upper_x(k))) cp.SetParameterUpperBound(x.data(), k, problem.upper_x(k));
  }
  ceres::Solver::Options so;
  so.minimizer_type = ceres::TRUST_REGION;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.use_nonmonotonic_steps = true;
  so.num_threads = 1;  // determinism
  so.max_num_iterations = max_iterations;
  so.function_tolerance = problem.options().tolerance;
  so.parameter_tolerance = 1e-10;
  so.gradient_tolerance = 1e-14;
  so.logging_type = ceres::SILENT;
  so.minimizer_progress_to_stdout = false;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &cp, &summary);
  if (!summary.IsSolutionUsable() || !x.allFinite()) {
    outcome.usable = false;
    outcome.note = "ceres: no usable solution (" + summary.message + ")";
    return outcome;
  }
  problem.from_x(x.data(), problem.natural());
  outcome.iterations = static_cast<int>(summary.iterations.size());
  outcome.converged = summary.termination_type == ceres::CONVERGENCE;
  std::ostringstream s;
  s << "ceres: " << nf << " free, " << outcome.iterations << " iterations, cost "
    << summary.initial_cost << " -> " << summary.final_cost << ", " << summary.message;
  outcome.note = s.str();
  return outcome;
}

namespace {

// Fitted coordinates scaled to O(1): u = (x − x0)/s with s = 1 for log parameters (a factor
// e), half the magnitude (at least 1e-3, or 1 at zero) for linear ones.
struct ScaledBox {
  Eigen::VectorXd x0, s;
  Eigen::VectorXd lo, hi;          // optimisation bounds: the true ones, else ±30 scales
  Eigen::VectorXd box_lo, box_hi;  // sampling box of the random starts: ±3 scales
  Eigen::VectorXd x_at(const std::vector<double>& u) const {
    return x0 + s.cwiseProduct(Eigen::Map<const Eigen::VectorXd>(u.data(), u.size()));
  }
};

ScaledBox scaled_box(const Problem& problem) {
  const int nf = problem.num_free();
  ScaledBox b;
  b.x0 = problem.to_x(problem.natural());
  b.s.resize(nf), b.lo.resize(nf), b.hi.resize(nf), b.box_lo.resize(nf), b.box_hi.resize(nf);
  for (int k = 0; k < nf; ++k) {
    const int i = problem.free()[k];
    const double x0 = b.x0[k];
    b.s[k] = problem.is_log(i) ? 1.0 : (x0 == 0.0 ? 1.0 : std::max(0.5 * std::abs(x0), 1e-3));
    b.lo[k] = std::max((problem.lower_x(k) - x0) / b.s[k], -30.0);
    b.hi[k] = std::min((problem.upper_x(k) - x0) / b.s[k], 30.0);
    b.box_lo[k] = std::max(b.lo[k], -3.0);
    b.box_hi[k] = std::min(b.hi[k], 3.0);
  }
  return b;
}

using Objective = std::function<double(const std::vector<double>&)>;

// One LN_BOBYQA run from u (moved to the point reached); returns the value there, inf when the
// start failed (the reason in `note`).
double bobyqa_from(Objective& objective, const ScaledBox& b, double tolerance, int max_iterations,
                   std::vector<double>& u, int& evaluations, std::string& note) {
  const int nf = static_cast<int>(u.size());
  auto trampoline = [](const std::vector<double>& v, std::vector<double>&, void* data) {
    return (*static_cast<Objective*>(data))(v);
  };
  nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(nf));
  opt.set_lower_bounds(std::vector<double>(b.lo.data(), b.lo.data() + nf));
  opt.set_upper_bounds(std::vector<double>(b.hi.data(), b.hi.data() + nf));
  opt.set_min_objective(+trampoline, &objective);
  opt.set_xtol_rel(1e-8);
  opt.set_ftol_rel(tolerance);
  opt.set_maxeval(std::max(4 * max_iterations, 10 * (nf + 1)));
  std::vector<double> step(nf);
  for (int k = 0; k < nf; ++k) step[k] = std::min(0.5, 0.25 * (b.hi[k] - b.lo[k]));
  opt.set_initial_step(step);
  double value = kInf;
  try {
    opt.optimize(u, value);
  } catch (const nlopt::roundoff_limited&) {
    value = objective(u);  // the point reached is still usable
  } catch (const std::exception& e) {
    note = std::string("nlopt: a start failed: ") + e.what();
    value = kInf;
  }
  evaluations += opt.get_numevals();
  return value;
}

}  // namespace

StageOutcome run_nlopt(Problem& problem, int starts, int max_iterations) {
  StageOutcome outcome;
  const int nf = problem.num_free();
  if (nf == 0) {
    outcome.converged = true;
    return outcome;
  }
  const ScaledBox box = scaled_box(problem);
  std::vector<double> natural = problem.natural();
  Objective objective = [&](const std::vector<double>& u) {
    const Eigen::VectorXd x = box.x_at(u);
    problem.from_x(x.data(), natural);
    const double c = problem.cost(natural);
    return std::isfinite(c) ? c : 1e300;
  };
  core::Rng rng(problem.options().seed);
  std::optional<core::Progress> progress;
  if (problem.options().progress)
    progress.emplace("nlopt multistart", static_cast<std::size_t>(std::max(starts, 1)));
  std::vector<double> best_u(nf, 0.0);
  double best = objective(best_u);
  int evaluations = 0;
  for (int start = 0; start < std::max(starts, 1); ++start) {
    std::vector<double> u(nf, 0.0);
    if (start > 0)
      for (int k = 0; k < nf; ++k) u[k] = rng.uniform(box.box_lo[k], box.box_hi[k]);
    for (int k = 0; k < nf; ++k) u[k] = std::clamp(u[k], box.lo[k], box.hi[k]);
    const double value = bobyqa_from(objective, box, problem.options().tolerance, max_iterations,
                                     u, evaluations, outcome.note);
    if (std::isfinite(value) && value < best) {
      best = value;
      best_u = u;
    }
    if (progress) progress->advance();
  }
  const Eigen::VectorXd x = box.x_at(best_u);
  problem.from_x(x.data(), problem.natural());
  outcome.converged = best < 1e300;
  outcome.iterations = evaluations;
  std::ostringstream note;
  note << "nlopt: LN_BOBYQA from " << std::max(starts, 1) << " starts (seed "
       << problem.options().seed << "), " << evaluations << " evaluations, best cost " << best;
  outcome.note = note.str();
  return outcome;
}

}  // namespace fitlib::fit::detail
