#pragma once
// Term-count selection for series models (Prony, retardation spectra): fit N = min..max terms
// and rank them by AIC, BIC and pyvisco's rule (smallest N whose cost ≤ 1.5 × the minimum).
// The table doubles as the accuracy-versus-time table of the benchmarks.
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/spectrum.hpp"

namespace fitlib::fit {

enum class TermRule { bic, aic, residual_ratio };
// Accuracy target of relaxation term selection: rms log10 error 0.00215 = 0.5 % rms, half
// pyvisco's published 0.0043 (docs/decisions.md "Relaxation terms: BIC or an accuracy target").
constexpr double kRelaxationAccuracyLog10 = 0.00215;
// spectrum (default where it applies): one smooth-spectrum fit (fit/spectrum.hpp), its positive
// terms are the count; sweep: fit N = min..max terms with free times and rank them by `rule`.
enum class TermMethod { spectrum, sweep };
TermMethod parse_term_method(const std::string& text);  // "spectrum|sweep"

TermRule parse_term_rule(const std::string& text);  // "bic|aic|ratio"
const char* to_string(TermRule rule);

struct TermOptions {
  int min_terms = 1;
  int max_terms = 0;     // 0: one per decade of the data's frequency span + 2, at most 40
  int solver_cap = 0;    // e.g. 13 (Abaqus), 6 (LS-DYNA hyperelastic); 0 = none
  TermRule rule = TermRule::bic;
  double residual_ratio = 1.5;  // pyvisco's rule: smallest N with cost ≤ ratio × minimum
  // Relaxation data (fit/relaxation.hpp): the smallest N whose linear solve reaches this rms
  // log10 error of M(t) is chosen when `rule` asks for more (docs/fitting.md "Relaxation data";
  // 0: off).
  double accuracy_log10 = kRelaxationAccuracyLog10;
  TermMethod method = TermMethod::spectrum;  // sweep where the spectrum does not apply
  SpectrumOptions spectrum;
  CompactOptions compact;  // the spectrum's terms merged to the fewest that keep its figures
};

struct TermRow {
  int terms = 0;
  double wall_time_s = 0.0;
  double rms_log10_storage = 0.0, rms_log10_loss = 0.0;
  double cost = 0.0, aic = 0.0, bic = 0.0;
  int n_free = 0;
  bool converged = false;
  bool failed = false;  // the fit threw; the message says why
  std::string message;
};

struct TermSelection {
  std::vector<TermRow> rows;  // one per N tried, increasing
  int by_aic = 0, by_bic = 0, by_ratio = 0;  // N chosen by each rule (over all N tried)
  int by_accuracy = 0;  // relaxation data: smallest N reaching TermOptions::accuracy_log10 (0: none)
  TermRule rule = TermRule::bic;
  int unconstrained = 0;  // N chosen by `rule`
  int chosen = 0;         // N chosen by `rule` among N ≤ solver_cap (= unconstrained without cap)
  // Cost of the cap: chosen vs unconstrained (1 = no penalty).
  double cap_cost_ratio = 1.0, cap_storage_rms_ratio = 1.0, cap_loss_rms_ratio = 1.0;
  FitResult result;       // the fit with `chosen` terms
  std::vector<std::string> messages;
  TermMethod method = TermMethod::sweep;
  bool relaxation = false;  // rows of relaxation data: rms_log10_storage is M(t)'s, no loss
  std::vector<SpectrumPathRow> spectrum_path;  // method spectrum: the λ path (GCV)
  double spectrum_lambda = 0.0;
};

// `make(N)` builds the model with N terms. Throws NumericalError if every N fails.
TermSelection select_terms(const std::function<model::ModelPtr(int)>& make,
                           const data::DynamicTestTable& table, const FitOptions& options,
                           const TermOptions& terms);

// Same with model::make_model(kind, options + {"terms": N}).
TermSelection select_terms(const std::string& kind, const nlohmann::json& model_options,
                           const data::DynamicTestTable& table, const FitOptions& options,
                           const TermOptions& terms);

// The term economy and the solver cap of `terms` on a spectrum selection made with
// `terms.compact.enabled` false (select_terms does both itself otherwise): card::fit_card decides
// the default objective on the smooth spectra and compacts only the one it keeps.
void compact_spectrum_selection(const std::function<model::ModelPtr(int)>& make, const data::DynamicTestTable& table,
                                const FitOptions& options, const TermOptions& terms, TermSelection& sel);

// N chosen by `rule` among the usable rows with N ≤ cap (cap ≤ 0: no cap); 0 if none.
int choose_terms(const std::vector<TermRow>& rows, TermRule rule, double residual_ratio = 1.5,
                 int cap = 0);

// Human table (N, time, rms, cost, AIC, BIC, marks for each rule) for the CLI and benchmarks.
std::string format_term_table(const TermSelection& selection);

}  // namespace fitlib::fit
