#pragma once
// Smooth relaxation spectrum (docs/fitting.md "Default: a smooth spectrum"): the term moduli of a
// series model on a dense log-spaced time grid over the admissible window, by non-negative
// least squares with a second-difference penalty whose weight λ is chosen by generalized
// cross-validation (GCV) along one path; the terms left positive are then polished on the exact
// objective in log space with their times held.
#include <functional>
#include <string>
#include <vector>

#include "fitlib/fit/fit.hpp"
#include "fitlib/fit/master_curve.hpp"

namespace fitlib::fit {

// Default objective of the smooth spectrum (docs/fitting.md "Default objective"): errors
// relative to each modulus, E′ weighted 80 (E″ 1) on squared residuals. The relative error is
// the log10 error to first order, and exact for the linear solve (no polish needed).
constexpr double kSpectrumStorageWeight = 80.0;
constexpr ResidualKind kSpectrumResidual = ResidualKind::relative;
// card::fit_card counts both moduli (weights 1:1) where the data allow it (docs/fitting.md
// "Default objective"); these weights are the E′-first default where they do not.

struct SpectrumOptions {
  double per_decade = 2.0;   // time constants per decade
  // The grid spans [10^-g / ω_max, 10^g / ω_min] of the data (g = grid_margin_decades, at most
  // the admissible margin): terms far beyond the data would take the relaxed modulus's place.
  double grid_margin_decades = 0.0;
  double lambda = -1.0;      // smoothness weight; < 0: chosen by GCV on the path below
  double lambda_min = 1e-7, lambda_max = 1e3;
  int lambda_steps = 31;     // log-spaced path from lambda_max down to lambda_min
  // Gauss–Newton polish on the exact log10 objective plus the same penalty (λ held).
  bool polish = true;
  // With a temperature law and ≥ 2 isotherms: the law's constants (started from the model-free
  // isotherm shifts) refined with the spectrum, moduli projected out, λ held.
  bool refine_law = true;
};

struct SpectrumPathRow {
  double lambda = 0.0, gcv = 0.0, effective_terms = 0.0;
  int terms = 0;             // positive moduli
  double residual_norm = 0.0;  // of the linearised (weighted) data residuals
};

struct SpectrumFit {
  FitResult result;          // the model with the positive terms only
  double lambda = 0.0;       // chosen
  int grid_terms = 0;        // time constants on the grid
  int polish_steps = 0;
  int law_rounds = 0, law_evaluations = 0;  // refinement of the temperature law's constants
  std::vector<SpectrumPathRow> path;
  double wall_time_s = 0.0;
};

// True when `make(1)` is a series model with linear moduli and no temperature law or a WLF,
// Arrhenius or polynomial one (the models fit_spectrum handles).
bool spectrum_applies(const std::function<model::ModelPtr(int)>& make);

// `make(N)` builds the series model with N terms. UsageError when spectrum_applies is false.
SpectrumFit fit_spectrum(const std::function<model::ModelPtr(int)>& make,
                         const data::DynamicTestTable& table, const FitOptions& options,
                         const SpectrumOptions& spectrum = {});

// A spectrum fit reduced to at most `max_terms` terms (a solver's limit, card/export.hpp):
// adjacent terms merged pairwise by Ward's criterion in ln τ (moduli summed, ln τ weighted by
// modulus) until `max_terms` remain, then the N-term model re-fitted from there with free
// times (fit(), automatic backend: NNLS start, Ceres in log space; a law's constants free too)
// and from the model's own start; the lower cost is kept.
FitResult cap_spectrum(const std::function<model::ModelPtr(int)>& make, const data::DynamicTestTable& table,
                       const FitOptions& options, const FitResult& spectrum, int max_terms);

// Term economy (docs/fitting.md "Term economy"): the fewest terms, merged from the spectrum's
// positive ones by Ward's criterion or evenly spaced in ln τ over them (the lower cost), with the
// moduli re-solved (times and relaxed modulus held), whose fit keeps the spectrum's figures: rms
// log10 E′ and E″ within rms_tolerance (the 10 %), the relaxed modulus within
// relaxed_tolerance, and tan δ as smooth: rms log10 of its ratio to the spectrum's tan δ (20 per
// decade over the data) at most tan_delta_tolerance (docs/decisions.md "Term economy: tan δ as
// smooth as the spectrum").
struct CompactOptions {
  bool enabled = true;
  double rms_tolerance = 0.10;
  double relaxed_tolerance = 0.05;
  double tan_delta_tolerance = 0.02;  // rms log10 (≈ 5 %)
  // A third placement: the equal-ripple density, denser where tan δ is large (docs/fitting.md
  // "Term economy", equal-ripple placement). Off by default: measured on pyvisco's master it
  // lowers E′ at 20 terms (0.0113 → 0.0096) but does not reach pyvisco's E″ or tan δ figures.
  bool equal_ripple = false;
};
FitResult compact_spectrum(const std::function<model::ModelPtr(int)>& make, const data::DynamicTestTable& table,
                           const FitOptions& options, const FitResult& spectrum, const CompactOptions& compact = {});

// Raw isotherms: the spectrum on the master of `curve` (pairwise shifts), then the shifts and
// the spectrum refined together by block coordinate descent: every shift but the anchor's
// (the isotherm nearest T_ref) by Brent on its own rows with the spectrum held (±0.5 decade),
// then the spectrum re-fitted on the re-shifted master; rounds while the cost falls by > 0.01 %.
// Shifts follow E′ only (the cost with loss weight 0), as the pairwise shifts do.
struct SpectrumMasterFit {
  MasterCurve curve;     // the refined shifts (WLF / Arrhenius refitted to them)
  SpectrumFit spectrum;  // on curve.master
  double pairwise_cost = 0.0;  // E′ cost of the spectrum on the pairwise shifts' master
  int rounds = 0;        // rounds kept
};
SpectrumMasterFit refine_shifts_with_spectrum(const std::function<model::ModelPtr(int)>& make,
                                              const data::DynamicTestTable& raw, MasterCurve curve,
                                              const FitOptions& options, const SpectrumOptions& spectrum = {},
                                              int max_rounds = 6);

}  // namespace fitlib::fit
