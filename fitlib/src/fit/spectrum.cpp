#include "fitlib/fit/spectrum.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "admissible.hpp"
#include "backends.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/timer.hpp"
#include "fitlib/fit/nnls.hpp"
#include "fitlib/fit/problem.hpp"

namespace fitlib::fit {
namespace {

const double kLn10 = std::log(10.0);

// Generalized cross-validation of the penalised solution on its positive set F:
// GCV = m ‖r‖² / (m − df)², df = tr(R_F (R_FᵀR_F + λ D_FᵀD_F)⁻¹ R_Fᵀ).
double effective_parameters(const Eigen::MatrixXd& r, const Eigen::MatrixXd& d, double lambda,
                            const std::vector<int>& positive) {
  const int k = static_cast<int>(positive.size());
  if (k == 0) return 0.0;
  Eigen::MatrixXd rf(r.rows(), k), df(d.rows(), k);
  for (int j = 0; j < k; ++j) {
    rf.col(j) = r.col(positive[j]);
    df.col(j) = d.col(positive[j]);
  }
  const Eigen::MatrixXd gram = rf.transpose() * rf;
  const Eigen::MatrixXd m = gram + lambda * df.transpose() * df;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(m);
  return ldlt.solve(gram).trace();
}

// A tall least-squares problem reduced by one QR to its square factor: ‖A y − b‖² =
// ‖R y − c‖² + outside, so every λ and active set works on the small R.
struct Reduced {
  Eigen::MatrixXd r;
  Eigen::VectorXd c;
  double outside = 0.0;
};

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

// min ‖R y − c‖² + λ‖D y‖² over y ≥ 0.
Eigen::VectorXd solve_penalised(const Reduced& red, const Eigen::MatrixXd& d, double lambda) {
  const int nc = static_cast<int>(red.r.cols());
  Eigen::MatrixXd big(nc + d.rows(), nc);
  big << red.r, std::sqrt(lambda) * d;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(nc + d.rows());
  rhs.head(nc) = red.c;
  return nnls(big, rhs).x;
}

// The exact log10 objective plus the same penalty, by Gauss–Newton on the non-negative
// moduli: the design is linearised about the model instead of the data (row scale 1/model,
// rhs from log(model/data)); steps are kept while the penalised objective falls. Relative
// residuals are already linear: nothing to do. Returns the steps taken; `y` is updated.
int polish_penalised(Problem& problem, const detail::LinearDesign& design, const Eigen::VectorXd& scale,
                     const Eigen::MatrixXd& d, double lambda, Eigen::VectorXd& y) {
  if (problem.options().residual != ResidualKind::log10) return 0;
  const std::vector<double> start = problem.natural();
  auto objective = [&](const Eigen::VectorXd& yy) {
    detail::apply_linear_solution(problem, design, yy.cwiseQuotient(scale));
    return 2.0 * problem.cost(problem.natural()) + lambda * (d * yy).squaredNorm();
  };
  const Eigen::MatrixXd scaled = design.a * scale.cwiseInverse().asDiagonal();
  double best = objective(y);
  int steps = 0;
  for (; steps < 8; ++steps) {
    const Eigen::VectorXd fitted = scaled * y;
    Eigen::MatrixXd a = scaled;
    Eigen::VectorXd b = design.b;
    for (int e = 0; e < a.rows(); ++e) {
      const ResidualEntry& en = problem.entries()[e];
      if (en.absolute || en.sqrt_weight == 0.0) continue;
      const double row_scale = en.sqrt_weight / (en.data * kLn10);
      const double model = en.data + (fitted[e] - design.b[e]) / row_scale;
      if (!(model > 0.0)) continue;  // keep the data linearisation for this row
      const double ratio = en.data / model;
      a.row(e) *= ratio;
      b[e] = ratio * fitted[e] - row_scale * en.data * std::log(model / en.data);
    }
    const Eigen::VectorXd next = solve_penalised(reduce(a, b), d, lambda);
    const double value = objective(next);
    if (!(value < best)) break;
    const double gain = (best - value) / best;
    y = next;
    best = value;
    if (gain < 1e-8) break;
  }
  problem.natural() = start;
  return steps;
}

struct PathPoint {
  Eigen::VectorXd y;
  SpectrumPathRow row;
};

}  // namespace

bool spectrum_applies(const std::function<model::ModelPtr(int)>& make) {
  const model::ModelPtr m = make(1);
  const auto series = detail::series_terms(m->parameters());
  if (series.empty()) return false;
  for (int i : series.moduli)
    if (!m->parameters()[i].linear) return false;
  const auto p = m->default_parameters();
  return m->temperature_law(p.data()).value("law", std::string("none")) == "none";
}

SpectrumFit fit_spectrum(const std::function<model::ModelPtr(int)>& make,
                         const data::DynamicTestTable& table, const FitOptions& options,
                         const SpectrumOptions& so) {
  const core::Stopwatch clock;
  if (!spectrum_applies(make))
    throw core::UsageError("spectrum fit: needs a series model (Prony) with linear moduli and no "
                           "temperature law; use --terms N");
  const model::DataSummary summary = summarize(table);
  // The grid spans the admissible window (docs/fitting.md "Admissible terms").
  AdmissibleWindow window;
  {
    const model::ModelPtr probe = make(1);
    const Problem probe_problem(probe, table, options, probe->initial_parameters(summary));
    window = detail::admissible_window(probe_problem, probe_problem.natural());
  }
  if (!window.applies) throw core::UsageError("spectrum fit: no admissible window for these data");
  const double shrink = std::pow(10.0, std::max(options.tau_margin_decades - so.grid_margin_decades, 0.0));
  const double tau_lo = window.tau_min_s * shrink, tau_hi = window.tau_max_s / shrink;
  const double decades = std::log10(tau_hi / tau_lo);
  const int n = std::max(2, static_cast<int>(std::lround(so.per_decade * decades)) + 1);
  const model::ModelPtr dense = make(n);
  const detail::SeriesTerms series = detail::series_terms(dense->parameters());
  std::vector<double> start = dense->initial_parameters(summary);
  for (int k = 0; k < n; ++k)
    start[series.times[k]] = tau_lo * std::pow(tau_hi / tau_lo, double(k) / (n - 1));
  FitOptions linear_options = options;
  Problem problem(dense, table, linear_options, start);
  detail::apply_admissible_bounds(problem, window);
  std::vector<int> linear;
  for (int i : problem.free())
    if (problem.specs()[i].linear) linear.push_back(i);
  problem.set_free(linear);
  const detail::LinearDesign design = detail::linear_design(problem);
  const int nc = static_cast<int>(design.column_param.size());
  const int m = static_cast<int>(design.a.rows());

  // Column scaling: a column's norm is the relative effect of its term on the data, so the
  // penalty acts on the spectrum's relative contributions (y = ‖a_c‖ x_c).
  Eigen::VectorXd scale(nc);
  for (int c = 0; c < nc; ++c) scale[c] = std::max(design.a.col(c).norm(), 1e-300);
  const Eigen::MatrixXd scaled = design.a * scale.cwiseInverse().asDiagonal();
  Reduced red = reduce(scaled, design.b);

  // Second differences over the term moduli in time order.
  std::vector<int> column_of_term(n, -1);
  for (int col = 0; col < nc; ++col)
    for (int t = 0; t < n; ++t)
      if (design.column_param[col] == series.moduli[t] && design.column_sign[col] > 0) column_of_term[t] = col;
  // The spectrum is taken as 0 just outside the grid (zero padding): mass piled at the window's
  // ends, where the data cannot tell a term from the relaxed or glassy limit, is penalised too.
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n, nc);
  const double stencil[3] = {1.0, -2.0, 1.0};
  for (int t = -1; t + 1 < n; ++t)
    for (int q = 0; q < 3; ++q) {
      const int term = t + q;
      if (term >= 0 && term < n && column_of_term[term] >= 0) d(t + 1, column_of_term[term]) = stencil[q];
    }

  auto solve = [&](double lambda) {
    PathPoint pt;
    pt.y = solve_penalised(red, d, lambda);
    std::vector<int> positive;
    for (int j = 0; j < nc; ++j)
      if (pt.y[j] > 0.0) positive.push_back(j);
    const double rss = (red.r * pt.y - red.c).squaredNorm() + red.outside;
    const double df = effective_parameters(red.r, d, lambda, positive);
    pt.row.lambda = lambda;
    pt.row.effective_terms = df;
    pt.row.residual_norm = std::sqrt(rss);
    pt.row.gcv = m > df ? m * rss / ((m - df) * (m - df)) : std::numeric_limits<double>::infinity();
    for (int t = 0; t < n; ++t) pt.row.terms += column_of_term[t] >= 0 && pt.y[column_of_term[t]] > 0.0;
    return pt;
  };

  SpectrumFit out;
  out.grid_terms = n;
  PathPoint best;
  best.row.gcv = std::numeric_limits<double>::infinity();
  if (so.lambda >= 0.0) {
    best = solve(so.lambda);
    out.path.push_back(best.row);
  } else {
    for (int s = 0; s < so.lambda_steps; ++s) {
      const double t = so.lambda_steps > 1 ? double(s) / (so.lambda_steps - 1) : 0.0;
      PathPoint pt = solve(so.lambda_max * std::pow(so.lambda_min / so.lambda_max, t));
      out.path.push_back(pt.row);
      if (pt.row.gcv < best.row.gcv) best = std::move(pt);
    }
  }
  out.lambda = best.row.lambda;
  if (so.polish) {
    const int steps = polish_penalised(problem, design, scale, d, out.lambda, best.y);
    out.polish_steps = steps;
  }
  detail::apply_linear_solution(problem, design, best.y.cwiseQuotient(scale));

  // The model with the positive terms only, their times held; an all-zero spectrum keeps one
  // removed term (modulus 0) so the card stays a series.
  std::vector<int> kept;
  for (int t = 0; t < n; ++t)
    if (problem.natural()[series.moduli[t]] > 0.0) kept.push_back(t);
  const bool none = kept.empty();
  if (none) kept.push_back(n / 2);
  const model::ModelPtr reduced = make(static_cast<int>(kept.size()));
  const detail::SeriesTerms rs = detail::series_terms(reduced->parameters());
  std::vector<bool> is_series(dense->size(), false);
  for (int t = 0; t < n; ++t) is_series[series.moduli[t]] = is_series[series.times[t]] = true;
  std::vector<double> values(reduced->size(), 0.0);
  std::vector<bool> reduced_series(reduced->size(), false);
  for (std::size_t t = 0; t < kept.size(); ++t) {
    values[rs.moduli[t]] = none ? 0.0 : problem.natural()[series.moduli[kept[t]]];
    values[rs.times[t]] = problem.natural()[series.times[kept[t]]];
    reduced_series[rs.moduli[t]] = reduced_series[rs.times[t]] = true;
  }
  // The other parameters (relaxed modulus, bulk modulus, ...) keep their order.
  std::size_t j = 0;
  for (std::size_t i = 0; i < dense->size(); ++i) {
    if (is_series[i]) continue;
    while (j < reduced->size() && reduced_series[j]) ++j;
    if (j < reduced->size()) values[j++] = problem.natural()[i];
  }
  FitOptions polish = options;
  polish.backend = Backend::nnls;
  polish.linear_start = false;
  polish.polish = false;  // polished above, with the penalty
  out.result = fit(reduced, table, polish, &values);
  std::ostringstream s;
  s << "smooth spectrum: " << n << " time constants (" << so.per_decade << " per decade over ["
    << tau_lo << ", " << tau_hi << "] s), second-difference penalty lambda "
    << out.lambda << (so.lambda >= 0.0 ? " (given)" : " (GCV)") << ", " << kept.size()
    << " positive terms kept";
  if (out.polish_steps > 0)
    s << ", polished on the exact log10 objective with the penalty (" << out.polish_steps << " Gauss-Newton steps)";
  out.result.messages.insert(out.result.messages.begin(), s.str());
  for (int i : rs.times) out.result.parameters[i].reason = "on the smooth spectrum's time grid (held)";
  out.result.backend_used = "spectrum+" + out.result.backend_used;
  out.wall_time_s = clock.seconds();
  out.result.metrics.wall_time_s = out.wall_time_s;
  return out;
}

}  // namespace fitlib::fit
