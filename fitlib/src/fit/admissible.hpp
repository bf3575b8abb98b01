#pragma once
// Admissible terms of series models (docs/fitting.md "Admissible terms"): the window of
// relaxation times the data can inform, a ceiling on each term's modulus, a floor on the relaxed
// modulus; applied as bounds before the solve and enforced after it (private to the fit module).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fitlib/fit/problem.hpp"

namespace fitlib::fit::detail {

// Series terms: a "viscous"-group parameter paired in order with a "time"-group constant, and
// the "elastic" relaxed modulus (-1 when none). Empty when the model has no such pairs. A
// compliance series (a retardation spectrum: its "elastic" parameter in 1/MPa) has the glassy
// compliance J_g there instead.
struct SeriesTerms {
  std::vector<int> moduli, times;
  int relaxed = -1;
  bool compliance = false;
  bool empty() const { return times.empty(); }
};
SeriesTerms series_terms(const std::vector<core::ParameterSpec>& specs);

// The window at the natural parameters `p` (the temperature law shifts the data first).
// applies = false when the model has no series terms or a temperature law of its own
// (ShiftLaw::other; then no bound is set).
AdmissibleWindow admissible_window(const Problem& problem, const std::vector<double>& p);

// The window over measured ranges (ω in rad/s after shifting, storage or M(t) in MPa):
// τ ∈ [1/(ω_max 10^m), 10^m/ω_min], moduli ≤ modulus_ceiling × storage_max when every modulus is
// linear, the relaxed modulus ≥ relaxed_floor × storage_min when it is linear, a compliance
// series' instantaneous modulus 1/J_g ≤ modulus_ceiling × storage_max. Frequency and relaxation
// fits share it.
AdmissibleWindow window_over(const SeriesTerms& series, const std::vector<core::ParameterSpec>& specs,
                             const FitOptions& options, double omega_min, double omega_max,
                             double storage_min, double storage_max);

// The window's own limits on parameter i: [τ_min, τ_max] for a time, [0, modulus_max] for a
// term modulus (with a ceiling), [relaxed_min, ∞) for the relaxed modulus (with a floor),
// [1/glassy_modulus_max, ∞) for a compliance series' J_g; nullopt for any other parameter.
std::optional<std::pair<double, double>> window_limits(const SeriesTerms& series, const AdmissibleWindow& window,
                                                       int i);

// Sets the window's bounds on the problem (times, moduli, relaxed modulus) and moves the
// current point inside them. Returns the number of values moved.
int apply_admissible_bounds(Problem& problem, const AdmissibleWindow& window);

// The message that records a window in a fit's messages ("admissible terms: ...").
std::string describe_window(const AdmissibleWindow& window, int moved);

}  // namespace fitlib::fit::detail
