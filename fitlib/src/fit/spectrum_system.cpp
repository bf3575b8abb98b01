#include "spectrum_system.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <nlopt.hpp>

#include "fitlib/fit/nnls.hpp"

namespace fitlib::fit::detail {
namespace {

// Generalized cross-validation of the penalised solution on its positive set F:
// GCV = m ‖r‖² / (m − df)², df = tr((G_FF + λ H_FF)⁻¹ G_FF), G = RᵀR, H = DᵀD.
double effective_parameters(const Eigen::MatrixXd& g, const Eigen::MatrixXd& h, double lambda,
                            const std::vector<int>& positive) {
  const int k = static_cast<int>(positive.size());
  if (k == 0) return 0.0;
  Eigen::MatrixXd gf(k, k), qf(k, k);
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b) {
      gf(a, b) = g(positive[a], positive[b]);
      qf(a, b) = gf(a, b) + lambda * h(positive[a], positive[b]);
    }
  return Eigen::LDLT<Eigen::MatrixXd>(qf).solve(gf).trace();
}

// Lawson–Hanson's active set on the normal equations Q y = r (Q = G + λH positive definite),
// warm-started from `passive`: first the start set is pruned until its solution is positive,
// then the usual outer loop. False when it does not reach the KKT conditions within its budget
// (the caller then solves with nnls()).
bool active_set(const Eigen::MatrixXd& q, const Eigen::VectorXd& r, std::vector<bool>& passive, Eigen::VectorXd& y) {
  const int n = static_cast<int>(q.rows());
  auto solve_on = [&](Eigen::VectorXd& z) {
    std::vector<int> p;
    for (int i = 0; i < n; ++i)
      if (passive[i]) p.push_back(i);
    z = Eigen::VectorXd::Zero(n);
    if (p.empty()) return;
    Eigen::MatrixXd qp(p.size(), p.size());
    Eigen::VectorXd rp(p.size());
    for (std::size_t a = 0; a < p.size(); ++a) {
      rp[a] = r[p[a]];
      for (std::size_t b = 0; b < p.size(); ++b) qp(a, b) = q(p[a], p[b]);
    }
    const Eigen::VectorXd zp = qp.llt().solve(rp);
    for (std::size_t a = 0; a < p.size(); ++a) z[p[a]] = zp[a];
  };
  Eigen::VectorXd z;
  for (bool pruned = true; pruned;) {  // the warm start: drop non-positive members
    solve_on(z);
    pruned = false;
    for (int i = 0; i < n; ++i)
      if (passive[i] && !(z[i] > 0.0)) passive[i] = false, pruned = true;
  }
  y = z;
  const double tolerance = 1e-12 * std::max(r.cwiseAbs().maxCoeff(), 1e-300);
  for (int outer = 0; outer < 3 * n; ++outer) {
    const Eigen::VectorXd w = r - q * y;
    int j = -1;
    for (int i = 0; i < n; ++i)
      if (!passive[i] && w[i] > tolerance && (j < 0 || w[i] > w[j])) j = i;
    if (j < 0) return true;
    passive[j] = true;
    for (int inner = 0; inner < 3 * n; ++inner) {
      solve_on(z);
      double alpha = 1.0;
      for (int i = 0; i < n; ++i)
        if (passive[i] && !(z[i] > 0.0)) alpha = std::min(alpha, y[i] / (y[i] - z[i]));
      if (alpha >= 1.0) break;
      y += alpha * (z - y);
      for (int i = 0; i < n; ++i)
        if (passive[i] && !(y[i] > 0.0)) passive[i] = false, y[i] = 0.0;
    }
    y = z;
    if (!(y.minCoeff() >= 0.0)) return false;
  }
  return false;
}

bool is_series(const SeriesTerms& s, int i) {
  return std::find(s.moduli.begin(), s.moduli.end(), i) != s.moduli.end() ||
         std::find(s.times.begin(), s.times.end(), i) != s.times.end();
}

}  // namespace

std::vector<double> non_series_values(const model::Model& m, const std::vector<double>& p) {
  const SeriesTerms s = series_terms(m.parameters());
  std::vector<double> out;
  for (int i = 0; i < static_cast<int>(p.size()); ++i)
    if (!is_series(s, i)) out.push_back(p[i]);
  return out;
}

void set_non_series_values(const model::Model& m, const std::vector<double>& values, std::vector<double>& p) {
  const SeriesTerms s = series_terms(m.parameters());
  for (std::size_t i = 0, j = 0; i < p.size() && j < values.size(); ++i)
    if (!is_series(s, static_cast<int>(i))) p[i] = values[j++];
}

Reduced reduce(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  const int m = static_cast<int>(a.rows()), nc = static_cast<int>(a.cols()), k = std::min(m, nc);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(a);
  Reduced out;
  out.r = Eigen::MatrixXd::Zero(nc, nc);
  out.r.topRows(k) = qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
  const Eigen::VectorXd qtb = qr.householderQ().transpose() * b;
  out.c = Eigen::VectorXd::Zero(nc);
  out.c.head(k) = qtb.head(k);
  out.outside = std::max(b.squaredNorm() - out.c.squaredNorm(), 0.0);
  return out;
}

NormalEquations normal_equations(const Reduced& red, const Eigen::MatrixXd& d) {
  return {red.r.transpose() * red.r, d.transpose() * d, red.r.transpose() * red.c};
}

Eigen::VectorXd solve_penalised(const Reduced& red, const Eigen::MatrixXd& d, const NormalEquations& ne,
                                double lambda, std::vector<bool>* passive) {
  const int nc = static_cast<int>(red.r.cols());
  std::vector<bool> all;
  std::vector<bool>& set = passive ? *passive : all;
  if (static_cast<int>(set.size()) != nc) set.assign(nc, true);
  Eigen::VectorXd y;
  if (active_set(ne.g + lambda * ne.h, ne.rhs, set, y)) return y;
  // Not settled (ill-conditioned Q): the QR-checked solver on the stacked system.
  Eigen::MatrixXd big(nc + d.rows(), nc);
  big << red.r, std::sqrt(lambda) * d;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nc + d.rows());
  rhs.head(nc) = red.c;
  y = nnls(big, rhs).x;
  for (int i = 0; i < nc; ++i) set[i] = y[i] > 0.0;
  return y;
}

Eigen::VectorXd solve_penalised(const Reduced& red, const Eigen::MatrixXd& d, double lambda) {
  return solve_penalised(red, d, normal_equations(red, d), lambda, nullptr);
}

void SpectrumSystem::relinearise() {
  design = linear_design(problem);
  red = reduce(design.a * scale.cwiseInverse().asDiagonal(), design.b);
  normal = normal_equations(red, d);
}

double SpectrumSystem::penalised(const Eigen::VectorXd& y, double lambda) const {
  return (red.r * y - red.c).squaredNorm() + red.outside + lambda * (d * y).squaredNorm();
}

SpectrumSystem make_spectrum_system(const model::ModelPtr& dense, const data::DynamicTestTable& table,
                                    const FitOptions& options, double tau_lo, double tau_hi,
                                    const std::vector<double>& held) {
  const SeriesTerms series = series_terms(dense->parameters());
  const int n = static_cast<int>(series.times.size());
  std::vector<double> start = dense->initial_parameters(summarize(table));
  for (int k = 0; k < n; ++k) start[series.times[k]] = tau_lo * std::pow(tau_hi / tau_lo, double(k) / (n - 1));
  set_non_series_values(*dense, held, start);
  SpectrumSystem s(Problem(dense, table, options, start));
  s.series = series;
  s.terms = n;
  apply_admissible_bounds(s.problem, admissible_window(s.problem, s.problem.natural()));
  std::vector<int> linear;
  for (int i : s.problem.free())
    if (s.problem.specs()[i].linear) linear.push_back(i);
  s.problem.set_free(linear);
  s.design = linear_design(s.problem);
  const int nc = static_cast<int>(s.design.column_param.size());
  // Column scaling: a column's norm is the relative effect of its term on the data, so the
  // penalty acts on the spectrum's relative contributions (y = ‖a_c‖ x_c).
  s.scale.resize(nc);
  for (int c = 0; c < nc; ++c) s.scale[c] = std::max(s.design.a.col(c).norm(), 1e-300);
  s.red = reduce(s.design.a * s.scale.cwiseInverse().asDiagonal(), s.design.b);
  // Second differences over the term moduli in time order, zero-padded: the spectrum is taken
  // as 0 just outside the grid, so mass piled at the window's ends (where the data cannot tell
  // a term from the relaxed or glassy limit) is penalised too.
  s.column_of_term.assign(n, -1);
  for (int col = 0; col < nc; ++col)
    for (int t = 0; t < n; ++t)
      if (s.design.column_param[col] == series.moduli[t] && s.design.column_sign[col] > 0) s.column_of_term[t] = col;
  s.d = Eigen::MatrixXd::Zero(n, nc);
  const double stencil[3] = {1.0, -2.0, 1.0};
  for (int t = -1; t + 1 < n; ++t)
    for (int q = 0; q < 3; ++q) {
      const int term = t + q;
      if (term >= 0 && term < n && s.column_of_term[term] >= 0) s.d(t + 1, s.column_of_term[term]) = stencil[q];
    }
  s.normal = normal_equations(s.red, s.d);
  return s;
}

PathPoint solve_at(const SpectrumSystem& s, double lambda, std::vector<bool>* passive) {
  PathPoint pt;
  pt.y = solve_penalised(s.red, s.d, s.normal, lambda, passive);
  const int nc = static_cast<int>(pt.y.size());
  const int m = static_cast<int>(s.design.a.rows());
  std::vector<int> positive;
  for (int j = 0; j < nc; ++j)
    if (pt.y[j] > 0.0) positive.push_back(j);
  const double rss = (s.red.r * pt.y - s.red.c).squaredNorm() + s.red.outside;
  const double df = effective_parameters(s.normal.g, s.normal.h, lambda, positive);
  pt.row.lambda = lambda;
  pt.row.effective_terms = df;
  pt.row.residual_norm = std::sqrt(rss);
  pt.row.gcv = m > df ? m * rss / ((m - df) * (m - df)) : std::numeric_limits<double>::infinity();
  for (int t = 0; t < s.terms; ++t) pt.row.terms += s.column_of_term[t] >= 0 && pt.y[s.column_of_term[t]] > 0.0;
  return pt;
}

int refine_law_constants(SpectrumSystem& s, double lambda, const std::vector<int>& constants) {
  const int k = static_cast<int>(constants.size());
  if (k == 0) return 0;
  Problem& p = s.problem;
  // Fitted coordinates: ln p for log parameters (C1, C2, E_a), p for the polynomial's C_k.
  auto to_x = [&](int i, double v) { return p.is_log(i) ? std::log(v) : v; };
  auto to_p = [&](int i, double x) { return p.is_log(i) ? std::exp(x) : x; };
  std::vector<double> x(k), lo(k), hi(k), step(k);
  for (int j = 0; j < k; ++j) {
    const int i = constants[j];
    x[j] = to_x(i, p.natural()[i]);
    lo[j] = p.is_log(i) ? (p.lower(i) > 0.0 ? std::log(p.lower(i)) : -HUGE_VAL) : p.lower(i);
    hi[j] = p.is_log(i) ? std::log(p.upper(i)) : p.upper(i);
    x[j] = std::clamp(x[j], lo[j], hi[j]);
    step[j] = p.is_log(i) ? 0.05 : std::max(0.05 * std::abs(x[j]), 1e-8);
  }
  int evaluations = 0;
  auto objective = [&](const std::vector<double>& xx) {
    ++evaluations;
    for (int j = 0; j < k; ++j) p.natural()[constants[j]] = to_p(constants[j], xx[j]);
    try {
      s.relinearise();
    } catch (const std::exception&) {
      return HUGE_VAL;  // a trial beyond the law's pole
    }
    const double v = s.penalised(solve_penalised(s.red, s.d, s.normal, lambda, nullptr), lambda);
    return std::isfinite(v) ? v : HUGE_VAL;
  };
  nlopt::opt opt(nlopt::LN_BOBYQA, static_cast<unsigned>(k));
  opt.set_lower_bounds(lo);
  opt.set_upper_bounds(hi);
  opt.set_initial_step(step);
  opt.set_ftol_rel(1e-9);
  opt.set_maxeval(60 * k);
  using Fn = decltype(objective);
  std::pair<Fn*, int> data{&objective, k};
  opt.set_min_objective(
      [](unsigned, const double* xx, double*, void* d) {
        auto& f = *static_cast<std::pair<Fn*, int>*>(d);
        return (*f.first)(std::vector<double>(xx, xx + f.second));
      },
      &data);
  const double start_value = objective(x);
  std::vector<double> best = x;
  double best_value = start_value;
  try {
    std::vector<double> xx = x;
    double v = start_value;
    opt.optimize(xx, v);
    if (v < best_value) best = xx, best_value = v;
  } catch (const std::exception&) {
    // roundoff-limited or a failed start: keep the best point seen at the start
  }
  objective(best);  // leaves the law and the design at the best point
  return evaluations;
}

}  // namespace fitlib::fit::detail
