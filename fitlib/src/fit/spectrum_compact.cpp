// The smooth spectrum made compact (docs/fitting.md "Term economy", issue 35 item 3): every term
// is a state variable at every integration point of an FE model, so the default card keeps the
// fewest terms that hold the spectrum's accuracy.
#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "admissible.hpp"
#include "fitlib/core/format.hpp"
#include "fitlib/fit/spectrum.hpp"
#include "spectrum_system.hpp"
#include "term_merge.hpp"

namespace fitlib::fit {
namespace {

using detail::Term;

// What the compact card must keep of the spectrum's fit.
struct Figures {
  double storage = 0.0, loss = 0.0, relaxed = 0.0;
  std::vector<double> log10_tan_delta;  // at 20 points per decade over the data's frequencies
  int tan_delta_sign_changes = 0;       // of d tanδ / d log f on that grid (reported)
};

Figures figures_of(const FitResult& r, const data::DynamicTestTable& table) {
  const detail::SeriesTerms s = detail::series_terms(r.model->parameters());
  Figures f{r.metrics.rms_log10_storage, r.metrics.rms_log10_loss, s.relaxed >= 0 ? r.values[s.relaxed] : 0.0, {}, 0};
  double lo = INFINITY, hi = 0.0;
  for (const auto& row : table.rows) lo = std::min(lo, row.condition.frequency_Hz), hi = std::max(hi, row.condition.frequency_Hz);
  if (!(hi > lo)) return f;
  model::TestCondition c = table.rows.front().condition;
  const int n = static_cast<int>(std::lround(20.0 * std::log10(hi / lo)));
  for (int k = 0; k <= n; ++k) {
    c.frequency_Hz = lo * std::pow(10.0, k / 20.0);
    const auto m = r.model->moduli(r.values.data(), c);
    f.log10_tan_delta.push_back(std::log10(m.loss / m.storage));
  }
  const auto& t = f.log10_tan_delta;
  for (std::size_t k = 2; k < t.size(); ++k) f.tan_delta_sign_changes += (t[k] - t[k - 1]) * (t[k - 1] - t[k - 2]) < 0.0;
  return f;
}

// rms log10 of the card's tan δ against the spectrum's on the grid: the ripple a coarse comb of
// terms adds (docs/decisions.md "Term economy: tan δ as smooth as the spectrum").
double tan_delta_rms(const Figures& f, const Figures& ref) {
  double sum = 0.0;
  const std::size_t n = std::min(f.log10_tan_delta.size(), ref.log10_tan_delta.size());
  for (std::size_t k = 0; k < n; ++k) sum += std::pow(f.log10_tan_delta[k] - ref.log10_tan_delta[k], 2);
  return n ? std::sqrt(sum / n) : 0.0;
}

bool keeps(const Figures& f, const Figures& ref, const CompactOptions& o) {
  const double slack = 1.0 + o.rms_tolerance;
  return f.storage <= slack * ref.storage + 1e-12 && f.loss <= slack * ref.loss + 1e-12 &&
         std::abs(f.relaxed - ref.relaxed) <= o.relaxed_tolerance * ref.relaxed &&
         !(tan_delta_rms(f, ref) > o.tan_delta_tolerance);
}

// `n` terms placed two ways over the spectrum's positive terms: merged by Ward's criterion
// (term_merge.hpp; exact where the spectrum is a few separate peaks) and evenly spaced in ln τ
// (where it is broad: merges bunch terms where it is large and leave gaps, each a ripple of E″);
// at each the moduli re-solved (NNLS on the same objective; exact for relative residuals,
// polished in log space for log10 ones) with the times and the relaxed modulus held. The lower
// cost is kept. `trial`: figures only (FitOptions::uncertainty false).
FitResult compact_fit(const std::function<model::ModelPtr(int)>& make, const data::DynamicTestTable& table,
                      const FitOptions& options, const FitResult& spectrum, const std::vector<Term>& terms, int n,
                      bool trial) {
  const model::ModelPtr m = make(n);
  std::vector<Term> even(n);
  const double lo = terms.front().log_tau, hi = terms.back().log_tau;
  for (int k = 0; k < n; ++k) even[k] = {1.0, n > 1 ? lo + (hi - lo) * k / (n - 1) : 0.5 * (lo + hi)};
  const detail::SeriesTerms ms = detail::series_terms(m->parameters());
  FitOptions held = options;
  held.uncertainty = !trial;
  held.backend = Backend::nnls;
  held.polish = options.residual == ResidualKind::log10;
  for (int i : ms.times) held.fixed.push_back(m->parameters()[i].name);
  if (ms.relaxed >= 0) held.fixed.push_back(m->parameters()[ms.relaxed].name);
  std::vector<double> start = detail::start_from_terms(*m, spectrum, detail::merge_to(terms, n));
  FitResult merged = fit(m, table, held, &start);
  start = detail::start_from_terms(*m, spectrum, even);
  FitResult spaced = fit(m, table, held, &start);
  const bool even_kept = spaced.metrics.cost < merged.metrics.cost;
  FitResult& r = even_kept ? spaced : merged;
  for (int i : ms.times)
    r.parameters[i].reason = even_kept ? "evenly spaced over the smooth spectrum's terms (held)"
                                       : "merged from the smooth spectrum's terms (held)";
  if (ms.relaxed >= 0) r.parameters[ms.relaxed].reason = "the smooth spectrum's (held)";
  return std::move(r);
}

}  // namespace

FitResult compact_spectrum(const std::function<model::ModelPtr(int)>& make, const data::DynamicTestTable& table,
                           const FitOptions& options, const FitResult& spectrum, const CompactOptions& o) {
  const std::vector<Term> terms = detail::positive_terms(spectrum);
  const int full = static_cast<int>(terms.size());
  if (full <= 1) return spectrum;
  const Figures ref = figures_of(spectrum, table);
  // Fewer terms keep the figures less often: bisect for the smallest count that keeps them. On that
  // same premise, when one term fewer than the spectrum does not keep them no count does: tried
  // first, it spares the bisection's trials where the spectrum cannot be reduced (pyvisco's master).
  int lo = 1, hi = full;
  std::optional<FitResult> best;
  int tried = 0;
  if (full > 2) {
    ++tried;
    FitResult first = compact_fit(make, table, options, spectrum, terms, full - 1, true);
    if (!keeps(figures_of(first, table), ref, o)) {
      std::ostringstream msg;
      msg << "term economy: the smooth spectrum's " << full << " terms kept (" << full - 1
          << " terms do not keep its figures within " << 100.0 * o.rms_tolerance << " % rms, "
          << 100.0 * o.relaxed_tolerance << " % relaxed modulus, " << o.tan_delta_tolerance << " tan delta)";
      FitResult kept = spectrum;
      kept.messages.push_back(msg.str());
      return kept;
    }
    hi = full - 1;
    best = std::move(first);
  }
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    FitResult r = compact_fit(make, table, options, spectrum, terms, mid, true);
    ++tried;
    if (keeps(figures_of(r, table), ref, o)) {
      hi = mid;
      best = std::move(r);
    } else {
      lo = mid + 1;
    }
  }
  if (!best || hi == full) return spectrum;
  best = compact_fit(make, table, options, spectrum, terms, hi, false);  // the count kept, assessed
  const Figures f = figures_of(*best, table);
  std::ostringstream msg;
  msg << "term economy: the smooth spectrum's " << full << " terms reduced to " << hi << " (" << tried
      << " counts tried; rms log10 storage " << core::format_number(ref.storage, 3) << " -> "
      << core::format_number(f.storage, 3) << ", loss " << core::format_number(ref.loss, 3) << " -> "
      << core::format_number(f.loss, 3) << ", relaxed modulus " << core::format_number(ref.relaxed, 4) << " -> "
      << core::format_number(f.relaxed, 4) << " MPa, tan delta slope sign changes " << ref.tan_delta_sign_changes
      << " -> " << f.tan_delta_sign_changes << ", rms log10 tan delta against the spectrum's "
      << core::format_number(tan_delta_rms(f, ref), 3) << "; kept within " << 100.0 * o.rms_tolerance << " % rms, "
      << 100.0 * o.relaxed_tolerance << " % relaxed modulus, " << o.tan_delta_tolerance << " tan delta)";
  best->messages.insert(best->messages.begin(), spectrum.messages.begin(), spectrum.messages.end());
  best->messages.push_back(msg.str());
  best->backend_used = "spectrum+economy+" + best->backend_used;
  return std::move(*best);
}

}  // namespace fitlib::fit
