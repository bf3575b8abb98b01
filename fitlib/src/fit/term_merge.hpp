#pragma once
// Private to the fit module: adjacent terms of a series merged pairwise by Ward's criterion
// (docs/fitting.md "A term cap on the spectrum"; relaxation fits, "Relaxation data").
#include <vector>

namespace fitlib::fit::detail {

struct Term {
  double modulus, log_tau;
};

// Merges the adjacent pair (terms sorted by ln τ) whose merge moves the least "mass" in ln τ
// (Ward's criterion E_a E_b / (E_a + E_b) · Δ(ln τ)²) until `n` terms remain; the merged term
// keeps the pair's modulus sum and its modulus-weighted mean ln τ (zeroth and first moments of
// the spectrum).
std::vector<Term> merge_to(std::vector<Term> terms, int n);

}  // namespace fitlib::fit::detail
