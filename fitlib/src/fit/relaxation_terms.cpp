// Term-count selection for relaxation data (docs/fitting.md "Relaxation data"): the rules of
// frequency data on a sweep of linear solves, stopped at an accuracy target where the data show
// no noise floor.
#include <algorithm>
#include <cmath>

#include "fitlib/core/error.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/fit/relaxation.hpp"
#include "relaxation_checks.hpp"
#include "spectrum_system.hpp"
#include "term_merge.hpp"
#include "term_sweep.hpp"

namespace fitlib::fit {
namespace {

// Smallest usable N (≤ cap when cap > 0) whose rms log10 error reaches `target`; 0 if none.
int first_reaching(const std::vector<TermRow>& rows, double target, int cap) {
  if (!(target > 0.0)) return 0;
  for (const auto& r : rows)
    if (!r.failed && (cap <= 0 || r.terms <= cap) && r.rms_log10_storage <= target) return r.terms;
  return 0;
}

// The rule's N, or the accuracy target's when that is smaller (returns true then); a message
// says which and why, and a warning when the count chosen is the edge of the search.
bool choose_relaxation_terms(const TermOptions& terms, int max_terms, TermSelection& sel,
                             std::vector<std::string>& warnings) {
  sel.by_accuracy = first_reaching(sel.rows, terms.accuracy_log10, 0);
  const int by_rule = choose_terms(sel.rows, terms.rule, terms.residual_ratio, 0);
  sel.unconstrained = sel.by_accuracy > 0 ? std::min(by_rule, sel.by_accuracy) : by_rule;
  sel.chosen = choose_terms(sel.rows, terms.rule, terms.residual_ratio, terms.solver_cap);
  if (sel.chosen == 0) throw core::NumericalError("relaxation terms: no usable fit");
  const int accurate = first_reaching(sel.rows, terms.accuracy_log10, terms.solver_cap);
  const std::string rule = to_string(terms.rule);
  if (accurate > 0 && accurate < sel.chosen) {
    sel.messages.push_back("relaxation terms: " + std::to_string(accurate) + " (the smallest N whose linear solve reaches rms log10 " +
                           core::format_number(terms.accuracy_log10, 3) + "); " + rule + " asked for " +
                           std::to_string(sel.chosen) + (sel.chosen == max_terms ? ", the edge of the search: no noise floor" : ""));
    sel.chosen = accurate;
    return true;
  }
  if (sel.chosen == max_terms && max_terms > 1) {
    warnings.push_back("relaxation terms: " + rule + " chose " + std::to_string(max_terms) +
                       ", the largest N tried (more terms kept paying: the data show no noise floor and no N reached rms log10 " +
                       core::format_number(terms.accuracy_log10, 3) + "); raise --max-terms or give --terms N");
  }
  return false;
}

// The terms of a fit with a positive modulus, in order of ln τ.
std::vector<detail::Term> active_terms(const FitResult& r) {
  const detail::SeriesTerms s = detail::series_terms(r.model->parameters());
  std::vector<detail::Term> out;
  for (std::size_t j = 0; j < s.times.size(); ++j)
    if (r.values[s.moduli[j]] > 0.0) out.push_back({r.values[s.moduli[j]], std::log(r.values[s.times[j]])});
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.log_tau < b.log_tau; });
  return out;
}

// The model with `terms`, started from them and the other values of `from`, polished.
FitResult refit_with(const std::string& kind, const nlohmann::json& model_options, const data::RelaxationTable& table,
                     const FitOptions& options, const std::vector<detail::Term>& terms, const FitResult& from) {
  nlohmann::json o = model_options.is_object() ? model_options : nlohmann::json::object();
  o["terms"] = static_cast<int>(terms.size());
  const model::ModelPtr m = model::make_model(kind, o);
  const detail::SeriesTerms s = detail::series_terms(m->parameters());
  std::vector<double> start(m->size(), 0.0);
  for (std::size_t j = 0; j < terms.size(); ++j) {
    start[s.moduli[j]] = terms[j].modulus;
    start[s.times[j]] = std::exp(terms[j].log_tau);
  }
  detail::set_non_series_values(*m, detail::non_series_values(*from.model, from.values), start);
  return fit_relaxation(m, table, options, &start);
}

// Unused terms dropped, then the cheapest adjacent pair (Ward's criterion) merged and the fit
// re-polished while its BIC does not rise or its cost stays within 0.1 % (+ 1e-10 per row, the
// rule for flagged terms of docs/fitting.md "Admissible terms"). The sweep's fixed grid splits a
// term between two nodes or adds one at noise level; this takes them back.
FitResult compact(const std::string& kind, const nlohmann::json& model_options, const data::RelaxationTable& table,
                  const FitOptions& options, FitResult fitted) {
  std::vector<detail::Term> terms = active_terms(fitted);
  const int before = static_cast<int>(detail::series_terms(fitted.model->parameters()).times.size());
  if (terms.empty() || !options.fixed.empty() || !options.polish) return fitted;
  FitResult kept = static_cast<int>(terms.size()) < before ? refit_with(kind, model_options, table, options, terms, fitted)
                                                            : std::move(fitted);
  int merged = 0;
  while (terms.size() > 1) {
    const std::vector<detail::Term> fewer = detail::merge_to(terms, static_cast<int>(terms.size()) - 1);
    FitResult trial = refit_with(kind, model_options, table, options, fewer, kept);
    const bool holds = trial.metrics.cost <= 1.001 * kept.metrics.cost + 1e-10 * table.rows.size();
    if (!holds && !(trial.metrics.bic <= kept.metrics.bic)) break;
    kept = std::move(trial);
    terms = active_terms(kept);
    ++merged;
  }
  const int after = static_cast<int>(terms.size());
  if (after < before)
    kept.messages.push_back("relaxation terms: " + std::to_string(before) + " polished, " +
                            std::to_string(before - after - merged) + " unused dropped, " + std::to_string(merged) +
                            " merged into a neighbour (BIC not higher or cost within 0.1 %): " + std::to_string(after) + " kept");
  return kept;
}

// The chosen N polished; when the rule chose it (not the accuracy target), N + 1, N + 2, … are
// polished too while the polished BIC falls: a linear solve on the fixed grid undervalues small
// N on short tables (9 rows: 1 term ranked first, 14.8 % mean error, where 3 polished terms fit).
FitResult polish_upward(const std::vector<FitResult>& results, int min_terms, const data::RelaxationTable& table,
                        const FitOptions& options, int solver_cap, bool by_target, TermSelection& sel) {
  FitResult best = fit_relaxation(results[sel.chosen - min_terms].model, table, options);
  if (by_target) return best;
  const int last = min_terms + static_cast<int>(results.size()) - 1;
  const int first = sel.chosen;
  for (int n = first + 1; n <= last && (solver_cap <= 0 || n <= solver_cap); ++n) {
    if (sel.rows[n - min_terms].failed) continue;
    FitResult next = fit_relaxation(results[n - min_terms].model, table, options);
    if (!(next.metrics.bic < best.metrics.bic)) break;
    best = std::move(next);
    sel.chosen = n;
  }
  if (sel.chosen > first)
    sel.messages.push_back("relaxation terms: " + std::to_string(sel.chosen) + " polished terms rank above the " +
                           std::to_string(first) + " the linear solves chose (polished BIC)");
  return best;
}

}  // namespace

TermSelection select_relaxation_terms(const std::string& kind, const nlohmann::json& model_options,
                                      const data::RelaxationTable& table, const FitOptions& options,
                                      const TermOptions& terms) {
  int max_terms = terms.max_terms;
  if (max_terms <= 0) {
    const auto s = detail::summarize_relaxation(table);
    max_terms = std::clamp(static_cast<int>(std::ceil(std::log10(s.omega_max_rad_s / s.omega_min_rad_s))) + 2, 1, 40);
    // 2N + 1 parameters < rows: the residual keeps a degree of freedom (BIC needs a variance).
    max_terms = std::max(std::min(max_terms, (static_cast<int>(table.rows.size()) - 2) / 2), 1);
  }
  const int min_terms = std::max(terms.min_terms, 1);
  if (max_terms < min_terms) throw core::UsageError("relaxation terms: max below min");
  TermSelection sel;
  sel.rule = terms.rule;
  sel.relaxation = true;
  // Each N is ranked on its linear solve (τ on the model's start grid); only the chosen N and
  // the trials after it are polished (docs/fitting.md, "Relaxation data").
  FitOptions linear_only = options;
  linear_only.polish = false;
  auto fit_n = [&](int n) {
    nlohmann::json o = model_options.is_object() ? model_options : nlohmann::json::object();
    o["terms"] = n;
    return fit_relaxation(model::make_model(kind, o), table, linear_only);
  };
  std::vector<FitResult> results = detail::sweep_terms(min_terms, max_terms, fit_n, terms, false, sel);
  std::vector<std::string> warnings;
  const bool by_target = choose_relaxation_terms(terms, max_terms, sel, warnings);
  sel.result = options.polish
                   ? compact(kind, model_options, table, options,
                             polish_upward(results, min_terms, table, options, terms.solver_cap, by_target, sel))
                   : std::move(results[sel.chosen - min_terms]);
  auto& q = sel.result.quality.warnings;
  q.insert(q.end(), warnings.begin(), warnings.end());
  return sel;
}

}  // namespace fitlib::fit
