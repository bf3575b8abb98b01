// Standard errors, 95 % intervals and identifiability from the Jacobian at the solution.
#include <Eigen/QR>
#include <algorithm>
#include <boost/algorithm/string/join.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <sstream>

#include "admissible.hpp"
#include "backends.hpp"
#include "scaled_spectrum.hpp"
#include "fitlib/core/error.hpp"

namespace fitlib::fit::detail {

namespace {

// A parameter with more than this weight in the null space moves along a direction the data do
// not see: its interval would be conditional on the unseen coordinate (structural components
// are O(0.01–1), numerical noise in exact null vectors O(1e-12)).
constexpr double kNullShare = 1e-6;
constexpr double kDominant = 0.3;          // |v_k| naming a parameter in a null-space vector
constexpr double kHighCorrelation = 0.99;
constexpr double kMeaningfulFactor = 10.0;  // widest per-term interval given (either way)

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Values, default reasons, cost and information criteria at the solution.
void record_solution(const Problem& problem, double cost, FitResult& result) {
  const auto& specs = problem.specs();
  const int n = problem.num_parameters(), m = problem.num_residuals(), nf = problem.num_free();
  const std::vector<double>& p = problem.natural();
  result.values = p;
  result.parameters.assign(n, ParameterResult{});
  for (int i = 0; i < n; ++i) {
    auto& pr = result.parameters[i];
    pr.name = specs[i].name;
    pr.unit = specs[i].unit;
    pr.value = p[i];
    pr.fixed = problem.user_fixed()[i];
    if (pr.fixed) pr.reason = "fixed by the user";
    else if (problem.is_log(i) && p[i] <= 0.0)
      pr.reason = "inactive: held at 0 by the non-negativity constraint";
    else pr.reason = "not fitted in the final stage";
  }
  FitMetrics& metrics = result.metrics;
  metrics.n_residuals = m;
  metrics.n_free = nf;
  metrics.cost = cost;
  const double variance_per_residual = std::max(2.0 * cost / m, 1e-300);
  metrics.aic = m * std::log(variance_per_residual) + 2.0 * nf;
  metrics.bic = m * std::log(variance_per_residual) + nf * std::log(static_cast<double>(m));
  problem.measure(p, metrics);
  metrics.n_active = 0;
}

// Names the parameters of every null-space direction and those without effect or with a share
// in the null space; returns each free parameter's null-space share.
Eigen::VectorXd report_null_space(const Problem& problem, const ScaledSpectrum& sp, FitResult& result) {
  const auto& specs = problem.specs();
  const int nf = problem.num_free();
  Identifiability& ident = result.identifiability;
  Eigen::VectorXd null_share = Eigen::VectorXd::Zero(nf);
  for (int d = sp.rank; d < nf; ++d) {
    std::vector<std::pair<double, std::string>> members;
    for (int k = 0; k < nf; ++k) {
      null_share[k] += sp.v(k, d) * sp.v(k, d);
      if (std::abs(sp.v(k, d)) >= kDominant) members.emplace_back(std::abs(sp.v(k, d)), specs[problem.free()[k]].name);
    }
    std::sort(members.begin(), members.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<std::string> names;
    for (const auto& mbr : members) names.push_back(mbr.second);
    ident.null_space.push_back(names);
    result.messages.push_back("not identifiable from these data (null-space direction " +
                              std::to_string(d - sp.rank + 1) + "): " + boost::algorithm::join(names, ", "));
  }
  for (int k = 0; k < nf; ++k)
    if (sp.norms[k] == 0.0 || null_share[k] > kNullShare) ident.not_identifiable.push_back(specs[problem.free()[k]].name);
  if (!ident.not_identifiable.empty())
    result.messages.push_back("not identifiable from these data (no effect, or a component in a "
                              "null-space direction): " + boost::algorithm::join(ident.not_identifiable, ", "));
  return null_share;
}

// The standard error and 95 % interval of free parameter k (index i), or the reason it has none.
bool set_interval(const Problem& problem, int k, const ScaledSpectrum& sp, const Eigen::VectorXd& null_share,
                  const Eigen::MatrixXd& cov_x, double t, bool series_term, ParameterResult& pr) {
  const int i = problem.free()[k];
  const double p_i = problem.natural()[i];
  const bool log = problem.is_log(i);  // log: interval in log space, exponentiated (positive)
  const double x = log ? std::log(p_i) : p_i;
  const double tol = 1e-9 * (1.0 + std::abs(x));
  if (sp.norms[k] == 0.0) return pr.reason = "not identifiable: no effect on the residuals", false;
  if (null_share[k] > kNullShare)
    return pr.reason = "not identifiable: rank-deficient Jacobian (see the null-space messages)", false;
  if (std::abs(x - problem.lower_x(k)) < tol || std::abs(x - problem.upper_x(k)) < tol)
    return pr.at_bound = true, pr.reason = "at its bound: the linear interval does not apply", false;
  const double se_x = std::sqrt(std::max(cov_x(k, k), 0.0));
  if (!std::isfinite(se_x)) return pr.reason = "variance not finite", false;
  const double se = log ? p_i * se_x : se_x;
  const double low = log ? std::exp(x - t * se_x) : x - t * se_x;
  const double high = log ? std::exp(x + t * se_x) : x + t * se_x;
  // A card holds only finite numbers (docs/decisions.md "No interval"): an interval that
  // overflows is no interval.
  if (!std::isfinite(se) || !std::isfinite(low) || !std::isfinite(high))
    return pr.reason = "interval not finite: the data barely inform this parameter", false;
  // A series term's interval over more than a factor kMeaningfulFactor either way tells an
  // engineer nothing (issue 35: the auto card's spanned two to three decades); the confidence
  // band of the curve is what the data determine.
  if (series_term && log && t * se_x > std::log(kMeaningfulFactor))
    return pr.reason = "interval wider than a factor 10 either way: the data determine the card's curve (its "
                       "confidence band), not this term",
           false;
  pr.reason.clear();
  pr.std_error = se;
  pr.ci95_low = low;
  pr.ci95_high = high;
  return true;
}

// Cov_x restricted to the parameters with an interval: what a card carries (fit.covariance).
ParameterCovariance usable_covariance(const Problem& problem, const Eigen::MatrixXd& cov_x,
                                      const std::vector<bool>& usable) {
  ParameterCovariance c;
  std::vector<int> kept;
  for (int k = 0; k < static_cast<int>(usable.size()); ++k)
    if (usable[k]) kept.push_back(k), c.index.push_back(problem.free()[k]), c.log.push_back(problem.is_log(problem.free()[k]));
  for (int a : kept) {
    c.matrix.emplace_back();
    for (int b : kept) c.matrix.back().push_back(cov_x(a, b));
  }
  return c;
}

// The posterior covariance of the fitted coordinates under the smooth spectrum's prior
// (docs/decisions.md "Confidence band under the smoothness prior"): s² (JᵀJ + λ PᵀP)⁺, P the
// zero-padded second differences of the free series moduli in τ order, each on the scale the
// spectrum penalises (its column norm ‖J_k‖, spectrum_system.cpp). The bare covariance gives
// every term of a dense grid its own variance: the band then spikes at every τ of the grid.
Eigen::MatrixXd smoothness_prior_covariance(const Problem& problem, const RowMatrix& jac, double s2, double lambda) {
  const int nf = problem.num_free();
  const SeriesTerms series = series_terms(problem.specs());
  std::vector<int> free_of(problem.num_parameters(), -1);
  for (int k = 0; k < nf; ++k) free_of[problem.free()[k]] = k;
  std::vector<std::pair<double, int>> terms;  // (τ, free index of its modulus)
  for (std::size_t t = 0; t < series.moduli.size(); ++t)
    if (free_of[series.moduli[t]] >= 0)
      terms.emplace_back(problem.natural()[series.times[t]], free_of[series.moduli[t]]);
  std::sort(terms.begin(), terms.end());
  const int n = static_cast<int>(terms.size());
  Eigen::MatrixXd prior = Eigen::MatrixXd::Zero(n, nf);
  const double stencil[3] = {1.0, -2.0, 1.0};
  for (int row = 0; row < n; ++row)  // rows t = −1 … n − 2 of the padded stencil
    for (int q = 0; q < 3; ++q) {
      const int term = row - 1 + q;
      if (term >= 0 && term < n) prior(row, terms[term].second) = stencil[q] * jac.col(terms[term].second).norm();
    }
  const Eigen::MatrixXd information = jac.transpose() * jac + lambda * prior.transpose() * prior;
  return s2 * information.completeOrthogonalDecomposition().pseudoInverse();
}

// The band of E′, E″ and tan δ at 20 frequencies per decade over the data (BandPoint): the
// gradient of each logarithm in the fitted coordinates x, σ² = gᵀ Cov_x g, interval exp(ln v ± tσ).
ConfidenceBand confidence_band(const Problem& problem, const Eigen::MatrixXd& cov_x, double t) {
  ConfidenceBand band;
  const auto& rows = problem.table().rows;
  if (rows.empty()) return band;
  double lo = INFINITY, hi = 0.0;
  for (const auto& row : rows) lo = std::min(lo, row.condition.frequency_Hz), hi = std::max(hi, row.condition.frequency_Hz);
  band.condition = rows.front().condition;
  const int n = problem.num_parameters(), nf = problem.num_free();
  const std::vector<double>& p = problem.natural();
  const int points = std::max(2, static_cast<int>(std::lround(20.0 * std::log10(hi / lo))) + 1);
  Eigen::MatrixXd jac(3, n);
  for (int k = 0; k < points; ++k) {
    model::TestCondition c = band.condition;
    c.frequency_Hz = lo * std::pow(hi / lo, double(k) / (points - 1));
    const auto m = problem.model().moduli(p.data(), c, jac);
    if (!(m.storage > 0.0) || !(m.loss > 0.0)) continue;
    Eigen::VectorXd gs(nf), gl(nf);
    for (int j = 0; j < nf; ++j) {
      const int i = problem.free()[j];
      const double dp_dx = problem.is_log(i) ? p[i] : 1.0;
      gs[j] = jac(0, i) * dp_dx / m.storage;
      gl[j] = jac(1, i) * dp_dx / m.loss;
    }
    const auto half = [&](const Eigen::VectorXd& g) { return t * std::sqrt(std::max(g.dot(cov_x * g), 0.0)); };
    const double hs = half(gs), hl = half(gl), ht = half(gl - gs);
    BandPoint b{c.frequency_Hz, m.storage, m.storage * std::exp(-hs), m.storage * std::exp(hs),
                m.loss, m.loss * std::exp(-hl), m.loss * std::exp(hl), m.loss / m.storage,
                m.loss / m.storage * std::exp(-ht), m.loss / m.storage * std::exp(ht)};
    const double all[] = {b.storage_low, b.storage_high, b.loss_low, b.loss_high, b.tan_delta_low, b.tan_delta_high};
    if (std::all_of(std::begin(all), std::end(all), [](double x) { return std::isfinite(x) && x > 0.0; }))
      band.points.push_back(b);
  }
  return band;
}

// Pairs of parameters with intervals whose correlation exceeds kHighCorrelation.
void report_correlations(const Problem& problem, const Eigen::MatrixXd& cov_x, const std::vector<bool>& usable,
                         FitResult& result) {
  const auto& specs = problem.specs();
  const int nf = problem.num_free();
  for (int a = 0; a < nf; ++a)
    for (int b = a + 1; b < nf; ++b) {
      if (!usable[a] || !usable[b]) continue;
      const double denom = std::sqrt(cov_x(a, a) * cov_x(b, b));
      if (!(denom > 0.0)) continue;
      const double corr = cov_x(a, b) / denom;
      if (std::abs(corr) > kHighCorrelation) {
        const std::string na = specs[problem.free()[a]].name, nb = specs[problem.free()[b]].name;
        result.identifiability.correlated.push_back({na, nb, corr});
        std::ostringstream s;
        s << "correlation " << corr << " between " << na << " and " << nb
          << " (their intervals are not independent)";
        result.messages.push_back(s.str());
      }
    }
}

}  // namespace

void assess(const Problem& problem, FitResult& result) {
  const int m = problem.num_residuals(), nf = problem.num_free();
  RowMatrix jac(m, std::max(nf, 1));
  Eigen::VectorXd r(m);
  if (!problem.evaluate(problem.natural(), r.data(), nf ? jac.data() : nullptr))
    throw core::NumericalError("fit: residuals or Jacobian not finite at the solution of model '" +
                               problem.model().kind() + "'");
  const double cost = 0.5 * r.squaredNorm();
  record_solution(problem, cost, result);
  result.identifiability = Identifiability{};
  if (nf == 0 || !problem.options().uncertainty) return;

  const ScaledSpectrum sp = scaled_spectrum(jac);
  result.identifiability.rank = sp.rank;
  result.identifiability.condition_number = sp.condition_number;
  result.metrics.rank = sp.rank;
  result.metrics.condition_number = sp.condition_number;
  const Eigen::VectorXd null_share = report_null_space(problem, sp, result);

  const int dof = m - nf;
  if (dof <= 0) {
    for (int k = 0; k < nf; ++k)
      result.parameters[problem.free()[k]].reason = "no residual degrees of freedom (" + std::to_string(m) +
                                                    " residuals, " + std::to_string(nf) + " free parameters)";
    result.messages.push_back("standard errors not estimable: " + std::to_string(m) + " residuals for " +
                              std::to_string(nf) + " free parameters");
    return;
  }
  const double t = boost::math::quantile(boost::math::students_t(dof), 0.975);
  const Eigen::MatrixXd cov_x = scaled_covariance(sp, 2.0 * cost / dof);
  std::vector<bool> usable(nf, false);
  const SeriesTerms series = series_terms(problem.specs());
  std::vector<bool> in_series(problem.num_parameters(), false);
  for (int i : series.moduli) in_series[i] = true;
  for (int i : series.times) in_series[i] = true;
  for (int k = 0; k < nf; ++k) {
    const int i = problem.free()[k];
    usable[k] = set_interval(problem, k, sp, null_share, cov_x, t, in_series[i], result.parameters[i]);
    if (usable[k]) ++result.metrics.n_active;
  }
  report_correlations(problem, cov_x, usable, result);
  const double lambda = problem.options().band_smoothness;
  result.band = confidence_band(
      problem, lambda > 0.0 ? smoothness_prior_covariance(problem, jac, 2.0 * cost / dof, lambda) : cov_x, t);
  result.covariance = usable_covariance(problem, cov_x, usable);
}

}  // namespace fitlib::fit::detail
