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

// `n` times in ln τ over [lo, hi] at the equal-ripple density (CompactOptions::equal_ripple): a
// comb Δ decades apart ripples E″ by a(Δ) = 4 exp(−π²/(Δ ln 10)) and E′ by ≈ (2/π) tan δ a(Δ)
// (relative; the Debye kernels' Fourier series), so the objective's weighted sum of squared
// ripples, w′ (2/π tan δ)² a² + w″ a², is least for n terms at ρ = ln(w′ (2/π tan δ)² + w″) /
// (2π²/ln 10) + C terms per decade (C for ∫ρ = n − 1; at least 0.2 per decade, so no stretch of
// the range goes without a term), tan δ the spectrum's at ω = 1/τ in the first row's condition
// (as figures_of): denser where tan δ is large, even where the weights make E″ lead.
std::vector<Term> equal_ripple(const FitResult& spectrum, const FitOptions& options, const data::DynamicTestTable& table,
                               double lo, double hi, int n) {
  constexpr int cells = 400;
  constexpr double floor_per_decade = 0.2;
  const double decades = (hi - lo) / std::log(10.0), two_k = 2.0 * M_PI * M_PI / std::log(10.0);
  model::TestCondition c = table.rows.front().condition;
  std::vector<double> g(cells);
  for (int k = 0; k < cells; ++k) {
    c.frequency_Hz = 1.0 / (2.0 * M_PI * std::exp(lo + (hi - lo) * (k + 0.5) / cells));
    const auto m = spectrum.model->moduli(spectrum.values.data(), c);
    const double ripple_ratio = 2.0 / M_PI * m.loss / m.storage;
    g[k] = std::log(options.storage_weight * ripple_ratio * ripple_ratio + options.loss_weight) / two_k;
  }
  const auto density = [&](int k, double shift) { return std::max(floor_per_decade, g[k] + shift); };
  const auto count = [&](double shift) {
    double sum = 0.0;
    for (int k = 0; k < cells; ++k) sum += density(k, shift);
    return sum * decades / cells;
  };
  double a = -1e3, b = 1e3;  // count() grows with the shift
  for (int it = 0; it < 100; ++it) (count(0.5 * (a + b)) < n - 1 ? a : b) = 0.5 * (a + b);
  std::vector<double> cumulative(cells + 1, 0.0);
  for (int k = 0; k < cells; ++k) cumulative[k + 1] = cumulative[k] + density(k, 0.5 * (a + b));
  std::vector<Term> out(n);
  int k = 0;
  for (int j = 0; j < n; ++j) {
    const double target = cumulative[cells] * j / (n - 1);
    while (k < cells - 1 && cumulative[k + 1] < target) ++k;
    const double within = std::clamp((target - cumulative[k]) / (cumulative[k + 1] - cumulative[k]), 0.0, 1.0);
    out[j] = {1.0, lo + (hi - lo) * (k + within) / cells};
  }
  return out;
}

// `n` terms placed two ways over the spectrum's positive terms: merged by Ward's criterion
// (term_merge.hpp; exact where the spectrum is a few separate peaks) and evenly spaced in ln τ
// (where it is broad: merges bunch terms where it is large and leave gaps, each a ripple of E″),
// and a third way with CompactOptions::equal_ripple (equal_ripple above);
// at each the moduli re-solved (NNLS on the same objective; exact for relative residuals,
// polished in log space for log10 ones) with the times and the relaxed modulus held. The lower
// cost is kept. `trial`: figures only (FitOptions::uncertainty false).
FitResult compact_fit(const std::function<model::ModelPtr(int)>& make, const data::DynamicTestTable& table,
                      const FitOptions& options, const FitResult& spectrum, const std::vector<Term>& terms, int n,
                      bool trial, const CompactOptions& o) {
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
  FitResult* r = even_kept ? &spaced : &merged;
  const char* reason = even_kept ? "evenly spaced over the smooth spectrum's terms (held)"
                                 : "merged from the smooth spectrum's terms (held)";
  FitResult rippled;
  if (o.equal_ripple && n > 1) {
    start = detail::start_from_terms(*m, spectrum, equal_ripple(spectrum, options, table, lo, hi, n));
    rippled = fit(m, table, held, &start);
    if (rippled.metrics.cost < r->metrics.cost) {
      r = &rippled;
      reason = "at the equal-ripple density over the smooth spectrum's terms (held)";
    }
  }
  for (int i : ms.times) r->parameters[i].reason = reason;
  if (ms.relaxed >= 0) r->parameters[ms.relaxed].reason = "the smooth spectrum's (held)";
  return std::move(*r);
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
    FitResult first = compact_fit(make, table, options, spectrum, terms, full - 1, true, o);
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
    FitResult r = compact_fit(make, table, options, spectrum, terms, mid, true, o);
    ++tried;
    if (keeps(figures_of(r, table), ref, o)) {
      hi = mid;
      best = std::move(r);
    } else {
      lo = mid + 1;
    }
  }
  if (!best || hi == full) return spectrum;
  best = compact_fit(make, table, options, spectrum, terms, hi, false, o);  // the count kept, assessed
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
