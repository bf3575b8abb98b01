#include "fitlib/fit/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/core/timer.hpp"
#include "fitlib/fit/master_curve.hpp"
#include "fitlib/fit/problem.hpp"
#include "law_constants.hpp"
#include "spectrum_system.hpp"

namespace fitlib::fit {
namespace {

using detail::PathPoint;
using detail::SpectrumSystem;

const double kLn10 = std::log(10.0);

// The exact log10 objective plus the same penalty, by Gauss–Newton on the non-negative
// moduli: the design is linearised about the model instead of the data (row scale 1/model,
// rhs from log(model/data)); steps are kept while the penalised objective falls. Relative
// residuals are already linear: nothing to do. Returns the steps taken; `y` is updated.
int polish_penalised(SpectrumSystem& s, double lambda, Eigen::VectorXd& y) {
  Problem& problem = s.problem;
  if (problem.options().residual != ResidualKind::log10) return 0;
  const detail::LinearDesign& design = s.design;
  const std::vector<double> start = problem.natural();
  auto objective = [&](const Eigen::VectorXd& yy) {
    detail::apply_linear_solution(problem, design, yy.cwiseQuotient(s.scale));
    return 2.0 * problem.cost(problem.natural()) + lambda * (s.d * yy).squaredNorm();
  };
  const Eigen::MatrixXd scaled = design.a * s.scale.cwiseInverse().asDiagonal();
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
    const Eigen::VectorXd next = detail::solve_penalised(detail::reduce(a, b), s.d, lambda);
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

// Where the law's constants start: fitted to the model-free isotherm shifts of the data
// (build_master_curve) when there are at least two isotherms; else the model's start, held
// (one temperature: the law has no effect on the fit). `refine` says whether to move them.
struct LawStart {
  bool refine = false;
  std::string note;
};

LawStart place_law(const model::Model& probe, const data::DynamicTestTable& table, std::vector<double>& p) {
  LawStart out;
  const model::TemperatureLawInfo info = probe.temperature_law_info();
  if (info.law == model::ShiftLaw::none || info.shift_parameters.empty()) return out;
  MasterCurveOptions mo;
  mo.reference_C = info.reference_C;
  try {
    const MasterCurve curve = build_master_curve(table, mo);
    if (curve.isotherms.size() < 2) {
      out.note = "one isotherm: the " + model::to_string(info.law) + " law is held at its start (no effect on the data)";
      return out;
    }
    std::vector<double> temperatures, log10_aT;
    for (const auto& iso : curve.isotherms) {
      temperatures.push_back(iso.temperature_C);
      log10_aT.push_back(iso.log10_aT);
    }
    const detail::LawConstants c = detail::fit_law_constants(
        info.law, temperatures, log10_aT, info.reference_C, static_cast<int>(info.shift_parameters.size()));
    for (std::size_t k = 0; k < c.values.size(); ++k) {
      const auto& spec = probe.parameters()[info.shift_parameters[k]];
      p[info.shift_parameters[k]] = std::clamp(c.values[k], spec.lower, spec.upper);
    }
    out.note = "law started from the model-free shifts of " + std::to_string(curve.isotherms.size()) +
               " isotherms (" + c.summary + ", rms " + core::format_number(c.rms_decades, 3) + " decades)";
  } catch (const std::runtime_error& e) {
    out.note = std::string("law started from the model's defaults (isotherm shifts unavailable: ") + e.what() + ")";
  }
  out.refine = true;
  return out;
}

struct Grid {
  double tau_lo = 0.0, tau_hi = 0.0;
  int n = 0;
};

// The grid spans the admissible window at the law's current constants (docs/fitting.md
// "Admissible terms"), less its margin beyond grid_margin_decades.
Grid grid_for(const std::function<model::ModelPtr(int)>& make, const data::DynamicTestTable& table,
              const FitOptions& options, const SpectrumOptions& so, const std::vector<double>& held) {
  const model::ModelPtr probe = make(1);
  std::vector<double> p = probe->initial_parameters(summarize(table));
  detail::set_non_series_values(*probe, held, p);
  const Problem probe_problem(probe, table, options, p);
  const AdmissibleWindow window = detail::admissible_window(probe_problem, probe_problem.natural());
  if (!window.applies) throw core::UsageError("spectrum fit: no admissible window for these data");
  const double shrink = std::pow(10.0, std::max(options.tau_margin_decades - so.grid_margin_decades, 0.0));
  Grid g;
  g.tau_lo = window.tau_min_s * shrink;
  g.tau_hi = window.tau_max_s / shrink;
  g.n = std::max(2, static_cast<int>(std::lround(so.per_decade * std::log10(g.tau_hi / g.tau_lo))) + 1);
  return g;
}

// λ given, or the GCV minimum over the log-spaced path (the path goes to `out`).
PathPoint choose_lambda(const SpectrumSystem& s, const SpectrumOptions& so, std::vector<SpectrumPathRow>& path) {
  path.clear();
  if (so.lambda >= 0.0) {
    PathPoint pt = detail::solve_at(s, so.lambda);
    path.push_back(pt.row);
    return pt;
  }
  PathPoint best;
  best.row.gcv = std::numeric_limits<double>::infinity();
  std::vector<bool> passive;  // each λ starts from the positive set of the previous one
  for (int k = 0; k < so.lambda_steps; ++k) {
    const double t = so.lambda_steps > 1 ? double(k) / (so.lambda_steps - 1) : 0.0;
    PathPoint pt = detail::solve_at(s, so.lambda_max * std::pow(so.lambda_min / so.lambda_max, t), &passive);
    path.push_back(pt.row);
    if (pt.row.gcv < best.row.gcv) best = std::move(pt);
  }
  return best;
}

// The model with the positive terms of the solved system only (above 1e-12 of the total modulus);
// an all-zero spectrum keeps one removed term (modulus 0) so the card stays a series.
std::pair<model::ModelPtr, std::vector<double>> positive_terms(const std::function<model::ModelPtr(int)>& make,
                                                                const SpectrumSystem& s) {
  const std::vector<double>& p = s.problem.natural();
  // Round-off is no term: elastic data (loss 0) left moduli of 3e-16 MPa beside G_inf 2.3 MPa.
  double total = s.series.relaxed >= 0 ? p[s.series.relaxed] : 0.0;
  for (int t = 0; t < s.terms; ++t) total += p[s.series.moduli[t]];
  std::vector<int> kept;
  for (int t = 0; t < s.terms; ++t)
    if (p[s.series.moduli[t]] > 1e-12 * total) kept.push_back(t);
  const bool none = kept.empty();
  if (none) kept.push_back(s.terms / 2);
  const model::ModelPtr reduced = make(static_cast<int>(kept.size()));
  const detail::SeriesTerms rs = detail::series_terms(reduced->parameters());
  std::vector<double> values(reduced->size(), 0.0);
  for (std::size_t t = 0; t < kept.size(); ++t) {
    values[rs.moduli[t]] = none ? 0.0 : p[s.series.moduli[kept[t]]];
    values[rs.times[t]] = p[s.series.times[kept[t]]];
  }
  detail::set_non_series_values(*reduced, detail::non_series_values(s.problem.model(), p), values);
  return {reduced, values};
}

// The spectrum's notes ahead of the fit's messages, and why the time constants (and refined law
// constants) carry no standard error of their own.
void annotate(SpectrumFit& out, const model::Model& reduced, const Grid& grid,
              const SpectrumOptions& so, const std::string& law_note) {
  const detail::SeriesTerms rs = detail::series_terms(reduced.parameters());
  const auto& v = out.result.values;
  const auto kept = std::count_if(rs.moduli.begin(), rs.moduli.end(), [&](int i) { return v[i] > 0.0; });
  std::ostringstream s;
  s << "smooth spectrum: " << grid.n << " time constants (" << so.per_decade << " per decade over ["
    << grid.tau_lo << ", " << grid.tau_hi << "] s), second-difference penalty lambda " << out.lambda
    << (so.lambda >= 0.0 ? " (given)" : " (GCV)") << ", " << kept << " positive terms kept";
  if (out.polish_steps > 0)
    s << ", polished on the exact log10 objective with the penalty (" << out.polish_steps << " Gauss-Newton steps)";
  std::vector<std::string> notes{s.str()};
  if (!law_note.empty()) notes.push_back(law_note);
  if (out.law_rounds > 0)
    notes.push_back("law constants refined with the spectrum (moduli projected out, lambda held): " +
                    std::to_string(out.law_rounds) + " round(s), " + std::to_string(out.law_evaluations) +
                    " evaluations");
  out.result.messages.insert(out.result.messages.begin(), notes.begin(), notes.end());
  for (int i : rs.times) out.result.parameters[i].reason = "on the smooth spectrum's time grid (held)";
  if (out.law_rounds > 0)
    for (int i : reduced.temperature_law_info().shift_parameters)
      out.result.parameters[i].reason = "refined with the smooth spectrum (moduli projected out, lambda held)";
}

}  // namespace

bool spectrum_applies(const std::function<model::ModelPtr(int)>& make) {
  const model::ModelPtr m = make(1);
  const auto series = detail::series_terms(m->parameters());
  if (series.empty()) return false;
  for (int i : series.moduli)
    if (!m->parameters()[i].linear) return false;
  return m->temperature_law_info().law != model::ShiftLaw::other;
}

SpectrumFit fit_spectrum(const std::function<model::ModelPtr(int)>& make, const data::DynamicTestTable& table,
                         const FitOptions& options, const SpectrumOptions& so) {
  const core::Stopwatch clock;
  if (!spectrum_applies(make))
    throw core::UsageError("spectrum fit: needs a series model (Prony) with linear moduli; use --terms N");
  const model::ModelPtr probe = make(1);
  std::vector<double> probe_values = probe->initial_parameters(summarize(table));
  const LawStart law = place_law(*probe, table, probe_values);
  std::vector<double> held = detail::non_series_values(*probe, probe_values);
  SpectrumFit out;
  std::optional<SpectrumSystem> sys;
  PathPoint best;
  Grid grid;
  // With a law: the spectrum at the law, the law's constants refined with λ held, and again on
  // the grid of the moved window until it stays (≤ 0.1 decade) or after 3 rounds.
  for (int round = 0; round < 3; ++round) {
    grid = grid_for(make, table, options, so, held);
    sys.emplace(detail::make_spectrum_system(make(grid.n), table, options, grid.tau_lo, grid.tau_hi, held));
    best = choose_lambda(*sys, so, out.path);
    if (!law.refine || !so.refine_law) break;
    const auto constants = sys->problem.model().temperature_law_info().shift_parameters;
    out.law_evaluations += detail::refine_law_constants(*sys, best.row.lambda, constants);
    best = detail::solve_at(*sys, best.row.lambda);
    ++out.law_rounds;
    held = detail::non_series_values(sys->problem.model(), sys->problem.natural());
    const Grid moved = grid_for(make, table, options, so, held);
    if (std::abs(std::log10(moved.tau_lo / grid.tau_lo)) <= 0.1 && std::abs(std::log10(moved.tau_hi / grid.tau_hi)) <= 0.1)
      break;
  }
  out.grid_terms = grid.n;
  out.lambda = best.row.lambda;
  if (so.polish) out.polish_steps = polish_penalised(*sys, out.lambda, best.y);
  detail::apply_linear_solution(sys->problem, sys->design, best.y.cwiseQuotient(sys->scale));

  auto [reduced, values] = positive_terms(make, *sys);
  FitOptions polish = options;
  polish.backend = Backend::nnls;
  polish.linear_start = false;
  polish.polish = false;  // polished above, with the penalty
  polish.band_smoothness = out.lambda;  // the band under the spectrum's smoothness prior
  const detail::SeriesTerms rs = detail::series_terms(reduced->parameters());
  const bool elastic = values[rs.moduli.front()] == 0.0;  // an all-zero spectrum: its one term is removed
  if (elastic) polish.fixed.push_back(reduced->parameters()[rs.moduli.front()].name);  // held at 0, not moved to 1
  out.result = fit(reduced, table, polish, &values);
  if (elastic) {
    out.result.messages.push_back("the smooth spectrum has no positive term: the data show no relaxation the "
                                  "series could hold; the card keeps one removed term (modulus 0)");
    out.result.parameters[rs.moduli.front()].reason = "removed term: the smooth spectrum has no positive term";
  }
  annotate(out, *reduced, grid, so, law.note);
  out.result.backend_used = "spectrum+" + out.result.backend_used;
  out.wall_time_s = clock.seconds();
  out.result.metrics.wall_time_s = out.wall_time_s;
  return out;
}

}  // namespace fitlib::fit
