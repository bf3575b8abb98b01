#pragma once
// Private: the sweep over term counts shared by dynamic and relaxation fits (docs/fitting.md,
// "Term-count selection by sweep").
#include <functional>
#include <vector>

#include "fitlib/fit/terms.hpp"

namespace fitlib::fit::detail {

// One fit per term count n = min_terms … max_terms: a row per n in sel.rows (its figures, or the
// failure's message; with note_failures also in sel.messages), and the counts AIC, BIC and the
// residual-ratio rule pick in sel.by_aic, by_bic, by_ratio. Returns the results in order (an
// empty one for a failed n).
std::vector<FitResult> sweep_terms(int min_terms, int max_terms, const std::function<FitResult(int)>& fit_n,
                                   const TermOptions& terms, bool note_failures, TermSelection& sel);

}  // namespace fitlib::fit::detail
