// Hyperelastic fits (fit/hyperelastic.hpp, docs/hyperelastic.md §"Fitting").
#include "fitlib/fit/hyperelastic.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/rng.hpp"
#include "fitlib/model/time_series.hpp"
#include "scaled_spectrum.hpp"

namespace fitlib::fit {
namespace {

using model::DeformationMode;

// The rows a fit uses, each with its residual scale: r = w (P_model − P_data)/scale.
struct Row {
  DeformationMode mode;
  double x, stress, scale;
};

struct Rows {
  std::vector<Row> rows;
  std::vector<std::string> messages;
};

Rows fitted_rows(const data::QuasiStaticTable& table, const model::HyperelasticLaw& law,
                 const HyperelasticFitOptions& o) {
  Rows out;
  int dropped = 0;
  bool volumetric = false;
  for (const auto& r : table.rows) {
    if (r.mode == DeformationMode::volumetric) {
      if (!law.compressible())
        throw core::InputError("a volumetric row needs a compressible law (--compressible)", r.source_file,
                               r.source_line);
      volumetric = true;
    }
    const auto w = o.mode_weights.find(r.mode);
    const double weight = w == o.mode_weights.end() ? 1.0 : w->second;
    if (weight == 0.0) continue;
    if (o.residual == StressResidual::relative && r.stress_MPa == 0.0) {
      ++dropped;  // the undeformed anchor: no relative error exists there
      continue;
    }
    const double scale = o.residual == StressResidual::relative ? std::abs(r.stress_MPa) : 1.0;
    out.rows.push_back({r.mode, r.abscissa, r.stress_MPa, scale / weight});
  }
  if (law.compressible() && !volumetric)
    throw core::InputError("a compressible law needs volumetric rows (mode volumetric, volume_ratio, pressure_MPa) "
                           "to fit D1",
                           table.source_files.empty() ? "" : table.source_files.front());
  if (dropped > 0)
    out.messages.push_back(std::to_string(dropped) + " row(s) with zero stress left out: a relative residual has no "
                           "scale there (use --residual absolute to keep them)");
  if (out.rows.empty()) throw core::InputError("no rows to fit", table.source_files.empty() ? "" : table.source_files[0]);
  return out;
}

class StressCost final : public ceres::CostFunction {
 public:
  StressCost(const model::HyperelasticLaw& law, const Rows& rows, int n) : law_(law), rows_(rows), n_(n) {
    set_num_residuals(static_cast<int>(rows.rows.size()));
    mutable_parameter_block_sizes()->push_back(n);
  }
  bool Evaluate(double const* const* p, double* residuals, double** jacobians) const override {
    std::vector<double> g(n_);
    for (std::size_t i = 0; i < rows_.rows.size(); ++i) {
      const Row& r = rows_.rows[i];
      if (!law_.outside_domain(p[0], r.mode, r.x).empty()) return false;
      const double P = law_.nominal_stress(p[0], r.mode, r.x, jacobians ? g.data() : nullptr);
      residuals[i] = (P - r.stress) / r.scale;
      if (!std::isfinite(residuals[i])) return false;
      if (jacobians && jacobians[0])
        for (int k = 0; k < n_; ++k) jacobians[0][i * n_ + k] = g[k] / r.scale;
    }
    return true;
  }

 private:
  const model::HyperelasticLaw& law_;
  const Rows& rows_;
  int n_;
};

struct Solve {
  std::vector<double> p;
  double cost = std::numeric_limits<double>::infinity();
  int iterations = 0;
  bool converged = false;
};

Solve solve(const model::Model& m, const Rows& rows, std::vector<double> p, int max_iterations) {
  const auto& specs = m.parameters();
  const int n = static_cast<int>(p.size());
  auto* cost = new StressCost(*m.hyperelastic(), rows, n);
  {  // a start outside the law's domain (Gent past locking) is no start: Ceres would stop there
    std::vector<double> r(rows.rows.size());
    const double* blocks[] = {p.data()};
    if (!cost->Evaluate(blocks, r.data(), nullptr)) {
      delete cost;
      return {};
    }
  }
  ceres::Problem::Options po;
  po.cost_function_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(po);
  problem.AddResidualBlock(cost, nullptr, p.data());
  for (int k = 0; k < n; ++k) {
    // Positive scales stay strictly inside their bound (a modulus 0 is no law).
    const double lower = specs[k].transform == core::Transform::log ? std::max(specs[k].lower, 1e-12) : specs[k].lower;
    if (std::isfinite(lower)) problem.SetParameterLowerBound(p.data(), k, lower + 1e-12 * std::abs(lower));
    if (std::isfinite(specs[k].upper)) problem.SetParameterUpperBound(p.data(), k, specs[k].upper);
  }
  ceres::Solver::Options so;
  so.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  so.linear_solver_type = ceres::DENSE_QR;
  so.num_threads = 1;  // determinism
  so.max_num_iterations = max_iterations;
  so.function_tolerance = 1e-12;
  so.parameter_tolerance = 1e-12;
  so.gradient_tolerance = 1e-14;
  so.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  Solve s;
  if (!summary.IsSolutionUsable() || !std::all_of(p.begin(), p.end(), [](double v) { return std::isfinite(v); }))
    return s;
  s.p = p;
  s.cost = summary.final_cost;
  s.iterations = static_cast<int>(summary.iterations.size());
  s.converged = summary.termination_type == ceres::CONVERGENCE;
  return s;
}

// The parameters the stress is linear in (ParameterSpec::linear), solved by least squares with
// the others held: the stress is homogeneous in them, so its gradient is the design matrix.
void solve_linear(const model::Model& m, const Rows& rows, std::vector<double>& p) {
  const auto& specs = m.parameters();
  std::vector<int> lin;
  for (std::size_t k = 0; k < specs.size(); ++k)
    if (specs[k].linear) lin.push_back(static_cast<int>(k));
  Eigen::MatrixXd A(rows.rows.size(), lin.size());
  Eigen::VectorXd b(rows.rows.size());
  std::vector<double> g(p.size());
  for (std::size_t i = 0; i < rows.rows.size(); ++i) {
    const Row& r = rows.rows[i];
    if (r.mode == DeformationMode::volumetric || !m.hyperelastic()->outside_domain(p.data(), r.mode, r.x).empty()) {
      A.row(i).setZero(), b[i] = 0.0;
      continue;
    }
    m.hyperelastic()->nominal_stress(p.data(), r.mode, r.x, g.data());
    for (std::size_t j = 0; j < lin.size(); ++j) A(i, j) = g[lin[j]] / r.scale;
    b[i] = r.stress / r.scale;
  }
  const Eigen::VectorXd c = A.colPivHouseholderQr().solve(b);
  for (std::size_t j = 0; j < lin.size(); ++j)
    if (std::isfinite(c[j])) p[lin[j]] = c[j];
  for (std::size_t k = 0; k < specs.size(); ++k)  // a positive scale stays positive
    if (specs[k].transform == core::Transform::log && !(p[k] > 0.0)) p[k] = specs[k].default_value;
}

// D1 from the volumetric rows' secant bulk modulus K = p/(1 − J) (D1 = 2/K), the start of D1.
void start_volumetric(const model::Model& m, const data::QuasiStaticTable& table, std::vector<double>& p) {
  if (!m.hyperelastic()->compressible()) return;
  double num = 0.0, den = 0.0;
  for (const auto& r : table.rows)
    if (r.mode == DeformationMode::volumetric) num += r.stress_MPa * (1.0 - r.abscissa), den += (1.0 - r.abscissa) * (1.0 - r.abscissa);
  const double K = num / den;
  if (K > 0.0 && std::isfinite(K)) p.back() = 2.0 / K;
}

// A start's non-linear parameters: uniform within finite bounds (clipped to ±10), log-spread
// around the default above a lower bound.
std::vector<double> draw_start(const model::Model& m, core::Rng& rng, std::vector<double> p) {
  const auto& specs = m.parameters();
  for (std::size_t k = 0; k < specs.size(); ++k) {
    const auto& s = specs[k];
    if (s.linear || s.group == "volumetric") continue;
    if (std::isfinite(s.lower) && std::isfinite(s.upper))
      p[k] = rng.uniform(std::max(s.lower, -10.0), std::min(s.upper, 10.0));
    else if (std::isfinite(s.lower))
      p[k] = s.lower + (s.default_value - s.lower) * std::pow(10.0, rng.uniform(-1.5, 1.5));
  }
  return p;
}

int nonlinear_count(const model::Model& m) {
  int n = 0;
  for (const auto& s : m.parameters()) n += !s.linear && s.group != "volumetric";
  return n;
}

void covariance(const model::Model& m, const Rows& rows, HyperelasticFitResult& r) {
  const int n = static_cast<int>(r.values.size()), nr = static_cast<int>(rows.rows.size());
  r.std_error.assign(n, std::nullopt), r.ci95_low.assign(n, std::nullopt), r.ci95_high.assign(n, std::nullopt);
  r.std_error_reason.assign(n, "");
  if (nr <= n) {
    r.std_error_reason.assign(n, "no residual degrees of freedom");
    return;
  }
  Eigen::MatrixXd J(nr, n);
  std::vector<double> g(n);
  for (int i = 0; i < nr; ++i) {
    m.hyperelastic()->nominal_stress(r.values.data(), rows.rows[i].mode, rows.rows[i].x, g.data());
    for (int k = 0; k < n; ++k) J(i, k) = g[k] / rows.rows[i].scale;
  }
  // The rank test on the column-scaled Jacobian, as the viscoelastic fits': units do not decide it.
  const detail::ScaledSpectrum sp = detail::scaled_spectrum(J);
  const bool full = sp.rank == n;
  const double s2 = 2.0 * r.cost / (nr - n);
  const double t = boost::math::quantile(boost::math::students_t(nr - n), 0.975);
  const Eigen::MatrixXd cov = detail::scaled_covariance(sp, s2);
  for (int k = 0; k < n; ++k) {
    if (!full) {
      r.std_error_reason[k] = "not identifiable: the Jacobian is rank-deficient";
      continue;
    }
    const double se = std::sqrt(cov(k, k));
    r.std_error[k] = se, r.ci95_low[k] = r.values[k] - t * se, r.ci95_high[k] = r.values[k] + t * se;
  }
}

void verdict(const HyperelasticFitOptions& o, HyperelasticFitResult& r) {
  for (const auto& f : r.figures) {
    const std::string mode = model::to_string(f.mode);
    if (f.rms_rel_error > o.rms_threshold)
      r.warnings.push_back(mode + ": rms relative error " + core::format_number(100 * f.rms_rel_error, 3) +
                           " % above " + core::format_number(100 * o.rms_threshold) + " % (max " +
                           core::format_number(100 * f.max_rel_error, 3) + " % at " +
                           model::abscissa_name(f.mode) + " " + core::format_number(f.max_at) + ")");
    if (std::abs(f.mean_rel_error) > o.bias_threshold && std::abs(f.mean_rel_error) > 0.5 * f.rms_rel_error)
      r.warnings.push_back(mode + ": the card lies systematically " + (f.mean_rel_error > 0 ? "above" : "below") +
                           " the data (mean relative error " + core::format_number(100 * f.mean_rel_error, 3) +
                           " %): the law cannot follow this mode's curve");
  }
  for (const auto& s : r.stability) {  // a law's end beyond the data is a fact of the law, not a fault of the fit
    if (s.unstable_from > 0.0 && !s.locking) r.warnings.push_back(describe(s) + ", beyond the data");
    if (s.unstable_from > 0.0 && s.locking) r.messages.push_back(describe(s) + ", beyond the data");
  }
}

}  // namespace

StressResidual parse_stress_residual(const std::string& text) {
  if (text == "relative") return StressResidual::relative;
  if (text == "absolute") return StressResidual::absolute;
  throw core::UsageError("unknown stress residual '" + text + "' (relative, absolute)");
}
std::string to_string(StressResidual r) { return r == StressResidual::relative ? "relative" : "absolute"; }

std::vector<ModeFigure> hyperelastic_figures(const model::HyperelasticLaw& law, const double* p,
                                             const data::QuasiStaticTable& table) {
  std::map<DeformationMode, ModeFigure> by_mode;
  for (const auto& row : table.rows) {
    if (row.stress_MPa == 0.0 || (row.mode == DeformationMode::volumetric && !law.compressible())) continue;
    ModeFigure& f = by_mode[row.mode];
    f.mode = row.mode;
    const double e = law.outside_domain(p, row.mode, row.abscissa).empty()
                         ? law.nominal_stress(p, row.mode, row.abscissa) / row.stress_MPa - 1.0
                         : std::numeric_limits<double>::infinity();
    if (f.count == 0) f.abscissa_min = f.abscissa_max = row.abscissa;
    f.abscissa_min = std::min(f.abscissa_min, row.abscissa), f.abscissa_max = std::max(f.abscissa_max, row.abscissa);
    ++f.count;
    f.rms_rel_error += e * e, f.mean_rel_error += e;
    if (std::abs(e) >= f.max_rel_error) f.max_rel_error = std::abs(e), f.max_at = row.abscissa;
  }
  std::vector<ModeFigure> out;
  for (auto& [mode, f] : by_mode) {
    f.rms_rel_error = std::sqrt(f.rms_rel_error / f.count), f.mean_rel_error /= f.count;
    out.push_back(f);
  }
  return out;
}

std::string describe(const StabilityFinding& s) {
  if (s.unstable_from <= 0.0) return {};
  return std::string(s.locking ? "locked (undefined) in " : "Drucker-unstable in ") + model::to_string(s.mode) +
         (s.tension ? " tension" : " compression") + " from stretch " + core::format_number(s.unstable_from, 4);
}

std::vector<StabilityFinding> drucker_findings(const model::HyperelasticLaw& law, const double* p,
                                               const data::QuasiStaticTable& table, const HyperelasticFitOptions& o) {
  std::vector<StabilityFinding> out;
  for (DeformationMode mode : {DeformationMode::uniaxial, DeformationMode::equibiaxial, DeformationMode::planar})
    for (bool tension : {true, false}) {
      StabilityFinding f{mode, tension, tension ? o.stability_max_stretch : o.stability_min_stretch};
      f.unstable_from = model::first_unstable_stretch(law, p, mode, f.checked_to);
      f.locking = f.unstable_from > 0.0 && !law.outside_domain(p, mode, f.unstable_from).empty();
      for (const auto& r : table.rows)  // within the data: a row of this mode at or past it
        if (f.unstable_from > 0.0 && r.mode == mode &&
            (tension ? r.abscissa >= f.unstable_from : r.abscissa <= f.unstable_from))
          f.inside_data = true;
      out.push_back(f);
    }
  return out;
}

HyperelasticFitResult fit_hyperelastic(const data::QuasiStaticTable& table, model::ModelPtr model,
                                       const HyperelasticFitOptions& o) {
  const model::HyperelasticLaw* law = model->hyperelastic();
  if (!law) throw core::UsageError("model '" + model->kind() + "' is not hyperelastic");
  model::MaxwellSeries series;
  if (model->maxwell_series(model->default_parameters().data(), &series))
    throw core::UsageError(model->kind() + ": fit its hyperelastic base to quasi-static tests and its Prony "
                           "series to dynamic ones, then combine the cards (card::visco_hyperelastic_card)");
  const Rows rows = fitted_rows(table, *law, o);
  HyperelasticFitResult r;
  r.model = model;
  r.messages = rows.messages;
  const int nonlinear = nonlinear_count(*model);
  r.starts = o.multistart > 0 ? o.multistart : nonlinear == 0 ? 1 : 20 * nonlinear;
  core::Rng rng(o.seed);
  std::vector<double> base = model->default_parameters();
  start_volumetric(*model, table, base);
  Solve best, best_stable;
  for (int k = 0; k < r.starts; ++k) {
    std::vector<double> p = k == 0 ? base : draw_start(*model, rng, base);
    solve_linear(*model, rows, p);
    const Solve s = solve(*model, rows, p, o.max_iterations);
    if (!(s.cost < best.cost) && !(s.cost < best_stable.cost)) continue;
    if (s.cost < best.cost) best = s;
    bool stable = true;
    for (const auto& f : drucker_findings(*law, s.p.data(), table, o)) stable = stable && !f.inside_data;
    if (stable && s.cost < best_stable.cost) best_stable = s;
  }
  if (best.p.empty()) throw core::NumericalError(model->kind() + ": no start of the fit converged to finite parameters");
  if (best_stable.p.empty()) {
    for (const auto& f : drucker_findings(*law, best.p.data(), table, o))
      if (f.inside_data)
        throw core::NumericalError(model->kind() + ": the fitted law is " + describe(f) +
                                   ", within the data: refused (try fewer terms or another model)");
  }
  if (best_stable.cost > best.cost)
    r.messages.push_back("the best start was Drucker-unstable within the data; kept the best stable one (cost " +
                         core::format_number(best_stable.cost, 4) + " against " + core::format_number(best.cost, 4) + ")");
  r.values = best_stable.p, r.cost = best_stable.cost, r.iterations = best_stable.iterations;
  r.converged = best_stable.converged;
  r.n_points = static_cast<int>(rows.rows.size()), r.n_free = static_cast<int>(r.values.size());
  covariance(*model, rows, r);
  r.figures = hyperelastic_figures(*law, r.values.data(), table);
  r.stability = drucker_findings(*law, r.values.data(), table, o);
  verdict(o, r);
  return r;
}

}  // namespace fitlib::fit
