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
  int tan_delta_sign_changes = 0;
};

// Sign changes of d tanδ / d log f at 20 points per decade over the data's frequencies (the
// figure docs/fitting.md compares with pyvisco's and ANSYS's cards).
int tan_delta_sign_changes(const FitResult& r, const data::DynamicTestTable& table) {
  double lo = INFINITY, hi = 0.0;
  for (const auto& row : table.rows) lo = std::min(lo, row.condition.frequency_Hz), hi = std::max(hi, row.condition.frequency_Hz);
  if (!(hi > lo)) return 0;
  model::TestCondition c = table.rows.front().condition;
  const int n = static_cast<int>(std::lround(20.0 * std::log10(hi / lo)));
  int changes = 0;
  double previous = 0.0, previous_slope = 0.0;
  for (int k = 0; k <= n; ++k) {
    c.frequency_Hz = lo * std::pow(10.0, k / 20.0);
    const auto m = r.model->moduli(r.values.data(), c);
    const double tan_delta = m.loss / m.storage;
    if (k > 0) {
      const double slope = tan_delta - previous;
      if (k > 1 && slope * previous_slope < 0.0) ++changes;
      previous_slope = slope;
    }
    previous = tan_delta;
  }
  return changes;
}

Figures figures_of(const FitResult& r, const data::DynamicTestTable& table) {
  const detail::SeriesTerms s = detail::series_terms(r.model->parameters());
  return {r.metrics.rms_log10_storage, r.metrics.rms_log10_loss, s.relaxed >= 0 ? r.values[s.relaxed] : 0.0,
          tan_delta_sign_changes(r, table)};
}

bool keeps(const Figures& f, const Figures& ref, const CompactOptions& o) {
  const double slack = 1.0 + o.rms_tolerance;
  return f.storage <= slack * ref.storage + 1e-12 && f.loss <= slack * ref.loss + 1e-12 &&
         std::abs(f.relaxed - ref.relaxed) <= o.relaxed_tolerance * ref.relaxed &&
         f.tan_delta_sign_changes <= ref.tan_delta_sign_changes + o.extra_sign_changes;
}

// The spectrum's positive terms merged (Ward, term_merge.hpp) to `n`, the moduli re-solved at the
// merged times (NNLS on the same objective; exact for relative residuals, polished in log space
// for log10 ones), the times held. `trial`: figures only (FitOptions::uncertainty false).
FitResult merged_fit(const std::function<model::ModelPtr(int)>& make, const data::DynamicTestTable& table,
                     const FitOptions& options, const FitResult& spectrum, const std::vector<Term>& terms, int n,
                     bool trial) {
  const model::ModelPtr m = make(n);
  const detail::SeriesTerms ms = detail::series_terms(m->parameters());
  std::vector<double> start = detail::start_from_terms(*m, spectrum, detail::merge_to(terms, n));
  FitOptions held = options;
  held.uncertainty = !trial;
  held.backend = Backend::nnls;
  held.polish = options.residual == ResidualKind::log10;
  for (int i : ms.times) held.fixed.push_back(m->parameters()[i].name);
  FitResult r = fit(m, table, held, &start);
  for (int i : ms.times) r.parameters[i].reason = "merged from the smooth spectrum's terms (held)";
  return r;
}

}  // namespace

FitResult compact_spectrum(const std::function<model::ModelPtr(int)>& make, const data::DynamicTestTable& table,
                           const FitOptions& options, const FitResult& spectrum, const CompactOptions& o) {
  const std::vector<Term> terms = detail::positive_terms(spectrum);
  const int full = static_cast<int>(terms.size());
  if (full <= 1) return spectrum;
  const Figures ref = figures_of(spectrum, table);
  // Fewer terms keep the figures less often: bisect for the smallest count that keeps them.
  int lo = 1, hi = full;
  std::optional<FitResult> best;
  int tried = 0;
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    FitResult r = merged_fit(make, table, options, spectrum, terms, mid, true);
    ++tried;
    if (keeps(figures_of(r, table), ref, o)) {
      hi = mid;
      best = std::move(r);
    } else {
      lo = mid + 1;
    }
  }
  if (!best || hi == full) return spectrum;
  best = merged_fit(make, table, options, spectrum, terms, hi, false);  // the count kept, assessed
  const Figures f = figures_of(*best, table);
  std::ostringstream msg;
  msg << "term economy: the smooth spectrum's " << full << " terms merged to " << hi << " (" << tried
      << " merges tried; rms log10 storage " << core::format_number(ref.storage, 3) << " -> "
      << core::format_number(f.storage, 3) << ", loss " << core::format_number(ref.loss, 3) << " -> "
      << core::format_number(f.loss, 3) << ", relaxed modulus " << core::format_number(ref.relaxed, 4) << " -> "
      << core::format_number(f.relaxed, 4) << " MPa, tan delta slope sign changes " << ref.tan_delta_sign_changes
      << " -> " << f.tan_delta_sign_changes << "; kept within " << 100.0 * o.rms_tolerance << " % rms, "
      << 100.0 * o.relaxed_tolerance << " % relaxed modulus)";
  best->messages.insert(best->messages.begin(), spectrum.messages.begin(), spectrum.messages.end());
  best->messages.push_back(msg.str());
  best->backend_used = "spectrum+merge+" + best->backend_used;
  return std::move(*best);
}

}  // namespace fitlib::fit
