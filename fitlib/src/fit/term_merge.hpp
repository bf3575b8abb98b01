#pragma once
// Private to the fit module: adjacent terms of a series merged pairwise by Ward's criterion
// (docs/fitting.md "A term cap on the spectrum"; relaxation fits, "Relaxation data").
#include <functional>
#include <vector>

#include "fitlib/fit/fit.hpp"

namespace fitlib::fit::detail {

struct Term {
  double modulus, log_tau;
};

// Merges the adjacent pair (terms sorted by ln τ) whose merge moves the least "mass" in ln τ
// (Ward's criterion E_a E_b / (E_a + E_b) · Δ(ln τ)²) until `n` terms remain; the merged term
// keeps the pair's modulus sum and its modulus-weighted mean ln τ (zeroth and first moments of
// the spectrum).
std::vector<Term> merge_to(std::vector<Term> terms, int n);

// The positive series terms of a fitted spectrum, sorted by ln τ.
std::vector<Term> positive_terms(const FitResult& spectrum);

// `make(n)` started at `terms` (n of them, by ln τ), the other parameters (relaxed modulus, law
// constants) as in `spectrum`.
std::vector<double> start_from_terms(const model::Model& m, const FitResult& spectrum, const std::vector<Term>& terms);

}  // namespace fitlib::fit::detail
