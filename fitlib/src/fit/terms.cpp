#include "fitlib/fit/terms.hpp"

#include "term_sweep.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "fitlib/core/enum_names.hpp"
#include "fitlib/core/error.hpp"
#include "fitlib/core/timer.hpp"

namespace fitlib::fit {

namespace {
constexpr core::EnumName<TermRule> kTermRuleNames[] = {{TermRule::bic, "bic"}, {TermRule::aic, "aic"},
    {TermRule::residual_ratio, "ratio"}, {TermRule::residual_ratio, "pyvisco"}};
constexpr core::EnumName<TermMethod> kTermMethodNames[] = {{TermMethod::spectrum, "spectrum"}, {TermMethod::sweep, "sweep"}};
}  // namespace

TermRule parse_term_rule(const std::string& text) { return core::parse_enum(kTermRuleNames, text, "term rule"); }
const char* to_string(TermRule rule) { return core::enum_name(kTermRuleNames, rule); }

TermMethod parse_term_method(const std::string& text) {
  return core::parse_enum(kTermMethodNames, text, "term method");
}

namespace {

TermRow row_of(const FitResult& r, double wall_time_s) {
  const FitMetrics& m = r.metrics;
  TermRow row;
  row.terms = r.model->options().value("terms", 0);
  row.wall_time_s = wall_time_s;
  row.rms_log10_storage = m.rms_log10_storage;
  row.rms_log10_loss = m.rms_log10_loss;
  row.cost = m.cost;
  row.aic = m.aic;
  row.bic = m.bic;
  row.n_free = m.n_free;
  row.converged = m.converged;
  return row;
}

double ratio(double a, double b) { return b > 0.0 ? a / b : 1.0; }

// The smooth-spectrum fit as a one-row selection (its positive terms are the count); with a
// solver cap below that count, a second row: the spectrum reduced to the cap (cap_spectrum).
TermSelection spectrum_selection(const std::function<model::ModelPtr(int)>& make,
                                 const data::DynamicTestTable& table, const FitOptions& options,
                                 const TermOptions& terms) {
  SpectrumFit s = fit_spectrum(make, table, options, terms.spectrum);
  TermSelection sel;
  sel.method = TermMethod::spectrum;
  sel.rule = terms.rule;
  const TermRow full = row_of(s.result, s.wall_time_s);
  sel.rows.push_back(full);
  sel.by_aic = sel.by_bic = sel.by_ratio = sel.unconstrained = sel.chosen = full.terms;
  sel.spectrum_path = std::move(s.path);
  sel.spectrum_lambda = s.lambda;
  sel.result = std::move(s.result);
  compact_spectrum_selection(make, table, options, terms, sel);
  return sel;
}

const TermRow* row_for(const std::vector<TermRow>& rows, int terms) {
  for (const auto& r : rows)
    if (r.terms == terms) return &r;
  return nullptr;
}

}  // namespace

void compact_spectrum_selection(const std::function<model::ModelPtr(int)>& make, const data::DynamicTestTable& table,
                                const FitOptions& options, const TermOptions& terms, TermSelection& sel) {
  const TermRow full = sel.rows.front();
  if (terms.compact.enabled) {
    const core::Stopwatch economy;
    FitResult compact = compact_spectrum(make, table, options, sel.result, terms.compact);
    if (compact.values.size() < sel.result.values.size()) {
      TermRow row = row_of(compact, economy.seconds());
      row.message = "term economy: ";
      sel.rows.push_back(row);
      sel.chosen = row.terms;
      sel.result = std::move(compact);
    }
  }
  if (terms.solver_cap <= 0 || sel.chosen <= terms.solver_cap) return;
  const core::Stopwatch clock;
  FitResult capped = cap_spectrum(make, table, options, sel.result, terms.solver_cap);
  const TermRow cap = row_of(capped, clock.seconds());
  sel.rows.push_back(cap);
  sel.chosen = cap.terms;
  sel.cap_cost_ratio = ratio(cap.cost, full.cost);
  sel.cap_storage_rms_ratio = ratio(cap.rms_log10_storage, full.rms_log10_storage);
  sel.cap_loss_rms_ratio = ratio(cap.rms_log10_loss, full.rms_log10_loss);
  std::ostringstream msg;
  msg << "solver cap " << terms.solver_cap << " terms: the smooth spectrum's " << full.terms
      << " terms reduced to " << cap.terms << " (re-fitted with free times); cost x"
      << sel.cap_cost_ratio << ", rms log10 storage " << full.rms_log10_storage << " -> " << cap.rms_log10_storage
      << " (x" << sel.cap_storage_rms_ratio << "), loss " << full.rms_log10_loss << " -> " << cap.rms_log10_loss
      << " (x" << sel.cap_loss_rms_ratio << ")";
  sel.messages.push_back(msg.str());
  capped.messages.insert(capped.messages.begin(), sel.result.messages.front());
  sel.result = std::move(capped);
}

int choose_terms(const std::vector<TermRow>& rows, TermRule rule, double ratio, int cap) {
  double best = std::numeric_limits<double>::infinity();
  int chosen = 0;
  double min_cost = best;
  for (const auto& r : rows)
    if (!r.failed && (cap <= 0 || r.terms <= cap)) min_cost = std::min(min_cost, r.cost);
  for (const auto& r : rows) {
    if (r.failed || (cap > 0 && r.terms > cap)) continue;
    if (rule == TermRule::residual_ratio) {
      if (r.cost <= ratio * min_cost) return r.terms;
      continue;
    }
    const double score = rule == TermRule::aic ? r.aic : r.bic;
    if (score < best) {
      best = score;
      chosen = r.terms;
    }
  }
  return chosen;
}

namespace detail {

std::vector<FitResult> sweep_terms(int min_terms, int max_terms, const std::function<FitResult(int)>& fit_n,
                                   const TermOptions& terms, bool note_failures, TermSelection& sel) {
  std::vector<FitResult> results;
  for (int n = min_terms; n <= max_terms; ++n) {
    TermRow row;
    row.terms = n;
    const core::Stopwatch clock;
    try {
      FitResult r = fit_n(n);
      row.rms_log10_storage = r.metrics.rms_log10_storage;
      row.rms_log10_loss = r.metrics.rms_log10_loss;
      row.cost = r.metrics.cost;
      row.aic = r.metrics.aic;
      row.bic = r.metrics.bic;
      row.n_free = r.metrics.n_free;
      row.converged = r.metrics.converged;
      results.push_back(std::move(r));
    } catch (const core::NumericalError& e) {
      row.failed = true;
      row.message = e.what();
      results.emplace_back();
      if (note_failures) sel.messages.push_back("terms " + std::to_string(n) + ": " + e.what());
    }
    row.wall_time_s = clock.seconds();
    sel.rows.push_back(row);
  }
  sel.by_aic = choose_terms(sel.rows, TermRule::aic, terms.residual_ratio, 0);
  sel.by_bic = choose_terms(sel.rows, TermRule::bic, terms.residual_ratio, 0);
  sel.by_ratio = choose_terms(sel.rows, TermRule::residual_ratio, terms.residual_ratio, 0);
  return results;
}

}  // namespace detail

TermSelection select_terms(const std::function<model::ModelPtr(int)>& make,
                           const data::DynamicTestTable& table, const FitOptions& options,
                           const TermOptions& terms) {
  if (terms.method == TermMethod::spectrum && spectrum_applies(make))
    return spectrum_selection(make, table, options, terms);
  TermSelection sel;
  sel.rule = terms.rule;
  int max_terms = terms.max_terms;
  if (max_terms <= 0) {
    const auto s = summarize(table);
    const double decades = std::log10(s.omega_max_rad_s / s.omega_min_rad_s);
    max_terms = std::clamp(static_cast<int>(std::ceil(decades)) + 2, 1, 40);
  }
  const int min_terms = std::max(terms.min_terms, 1);
  if (max_terms < min_terms)
    throw core::UsageError("select_terms: max terms " + std::to_string(max_terms) +
                           " below min terms " + std::to_string(min_terms));
  std::vector<FitResult> results = detail::sweep_terms(
      min_terms, max_terms, [&](int n) { return fit(make(n), table, options); }, terms, true, sel);
  sel.unconstrained = terms.rule == TermRule::aic ? sel.by_aic
                      : terms.rule == TermRule::bic ? sel.by_bic
                                                    : sel.by_ratio;
  if (sel.unconstrained == 0)
    throw core::NumericalError("select_terms: every term count from " + std::to_string(min_terms) +
                               " to " + std::to_string(max_terms) + " failed");
  sel.chosen = choose_terms(sel.rows, terms.rule, terms.residual_ratio, terms.solver_cap);
  if (sel.chosen == 0)
    throw core::NumericalError("select_terms: no usable fit within the solver cap of " +
                               std::to_string(terms.solver_cap) + " terms");
  const TermRow* chosen = row_for(sel.rows, sel.chosen);
  const TermRow* free = row_for(sel.rows, sel.unconstrained);
  sel.cap_cost_ratio = ratio(chosen->cost, free->cost);
  sel.cap_storage_rms_ratio = ratio(chosen->rms_log10_storage, free->rms_log10_storage);
  sel.cap_loss_rms_ratio = ratio(chosen->rms_log10_loss, free->rms_log10_loss);
  if (sel.chosen != sel.unconstrained) {
    std::ostringstream s;
    s << "solver cap " << terms.solver_cap << " terms: " << sel.chosen << " terms instead of "
      << sel.unconstrained << "; cost x" << sel.cap_cost_ratio << ", rms log10 storage x"
      << sel.cap_storage_rms_ratio << ", loss x" << sel.cap_loss_rms_ratio;
    sel.messages.push_back(s.str());
  }
  sel.result = std::move(results[sel.chosen - min_terms]);
  return sel;
}

TermSelection select_terms(const std::string& kind, const nlohmann::json& model_options,
                           const data::DynamicTestTable& table, const FitOptions& options,
                           const TermOptions& terms) {
  return select_terms(
      [&](int n) {
        nlohmann::json o = model_options.is_object() ? model_options : nlohmann::json::object();
        o["terms"] = n;
        return model::make_model(kind, o);
      },
      table, options, terms);
}

std::string format_term_table(const TermSelection& sel) {
  std::ostringstream s;
  char line[256];
  if (sel.method == TermMethod::spectrum) {
    std::snprintf(line, sizeof line, "%12s %12s %10s %8s %14s\n", "lambda", "GCV", "eff_terms", "terms",
                  "residual_norm");
    s << line;
    for (const auto& r : sel.spectrum_path) {
      std::snprintf(line, sizeof line, "%12.4g %12.6g %10.2f %8d %14.6g%s\n", r.lambda, r.gcv,
                    r.effective_terms, r.terms, r.residual_norm,
                    r.lambda == sel.spectrum_lambda ? "  <- chosen (GCV)" : "");
      s << line;
    }
    for (std::size_t k = 0; k < sel.rows.size(); ++k) {
      const TermRow& r = sel.rows[k];
      std::snprintf(line, sizeof line, "%s%d terms, rms log10 E' %.5f, E'' %.5f, cost %.6g, %.3f ms%s\n",
                    k == 0 ? "" : r.message.empty() ? "solver cap: " : r.message.c_str(), r.terms, r.rms_log10_storage, r.rms_log10_loss, r.cost,
                    1e3 * r.wall_time_s, r.terms == sel.chosen ? "  <- chosen" : "");
      s << line;
    }
    return s.str();
  }
  const bool relaxation = sel.relaxation;  // one modulus, M(t): its rms in the storage slot
  std::snprintf(line, sizeof line, "%5s %10s %10s %10s %12s %12s %12s  %s\n", "terms", "time_ms",
                relaxation ? "rms_M(t)" : "rms_E'", relaxation ? "" : "rms_E''",
                "cost", "AIC", "BIC", "chosen by");
  s << line;
  for (const auto& r : sel.rows) {
    std::string marks;
    if (r.terms == sel.by_aic) marks += " aic";
    if (r.terms == sel.by_bic) marks += " bic";
    if (r.terms == sel.by_ratio) marks += " ratio";
    if (r.terms == sel.by_accuracy) marks += " accuracy";
    if (r.terms == sel.chosen) marks += " <- chosen";
    if (r.failed) marks += " FAILED: " + r.message;
    char loss[16] = "";
    if (!relaxation) std::snprintf(loss, sizeof loss, "%10.5f", r.rms_log10_loss);
    std::snprintf(line, sizeof line, "%5d %10.3f %10.5f %10s %12.6g %12.6g %12.6g %s\n", r.terms, 1e3 * r.wall_time_s,
                  r.rms_log10_storage, loss, r.cost, r.aic, r.bic, marks.c_str());
    s << line;
  }
  return s.str();
}

}  // namespace fitlib::fit
