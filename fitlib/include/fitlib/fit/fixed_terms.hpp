#pragma once
// A fixed number of series terms fitted fast (docs/fitting.md "Fixed term counts", issue 35
// item 5): the moduli by NNLS on a log grid of N time constants over the data window; free time
// constants only where they pay, started from a denser NNLS whose terms are merged to N.
#include <functional>
#include <optional>

#include "fitlib/fit/fit.hpp"

namespace fitlib::fit {

struct FixedTermOptions {
  // At or above this many terms per decade of data the grid alone is kept (free times do not
  // pay at the smooth spectrum's density).
  double grid_per_decade = 2.0;
  // The polish's start: NNLS on this many time constants per decade of data, its positive terms
  // merged pairwise (Ward's criterion) down to N.
  double dense_per_decade = 3.0;
  // Iteration budget of the free-time polish (Ceres LM, every parameter free). An iteration
  // budget rather than a wall-time one: same input, same card on any machine.
  int polish_iterations = 100;
  // Relative fall of the cost per iteration below which the polish stops (Ceres's function
  // tolerance; the fit's own tolerance when that is looser): below the polish's stated gain.
  double polish_tolerance = 1e-6;
  // The polish is kept only when it lowers the objective by at least this fraction of the grid's.
  double polish_gain = 0.01;
};

// `make(n)` is a series model with linear moduli and no temperature law (spectrum_applies);
// std::nullopt when it is not, when `options` are not the automatic backend's without fixed
// parameters, or when there are fewer residuals than twice the free fit's parameters (then
// fit() as before, whose verdict says the data do not determine the card).
std::optional<FitResult> fit_fixed_terms(const std::function<model::ModelPtr(int)>& make,
                                         const data::DynamicTestTable& table, const FitOptions& options, int terms,
                                         const FixedTermOptions& fixed = {});

}  // namespace fitlib::fit
